#include "denoise_reference.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vplkit::reference {

namespace {

using Vec3d = std::array<double, 3>;

Vec3d xyz(const Texel4& t) {
    return {t[0], t[1], t[2]};
}
double dot3(const Vec3d& a, const Vec3d& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3d sub(const Vec3d& a, const Vec3d& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

double divisor(double albedo, double albedo_floor) {
    return std::max(albedo, albedo_floor);
}

double plane_weight(const Vec3d& p, const Vec3d& n, const Vec3d& q, double sigma) {
    return std::exp(-std::abs(dot3(n, sub(q, p))) / sigma);
}
double normal_weight(const Vec3d& n, const Vec3d& m, double sigma) {
    return std::pow(std::max(dot3(n, m), 0.0), sigma);
}

}  // namespace

double luminance(const Texel4& c) {
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

DenoiseImage demodulate(const DenoiseImage& radiance, const DenoiseImage& albedo, const DenoiseImage& position,
                        double albedo_floor) {
    DenoiseImage out(radiance.width, radiance.height);
    for (size_t i = 0; i < out.texels.size(); ++i) {
        if (position.texels[i][3] <= 0.5) continue;
        for (int c = 0; c < 3; ++c)
            out.texels[i][c] = radiance.texels[i][c] / divisor(albedo.texels[i][c], albedo_floor);
    }
    return out;
}

DenoiseImage remodulate(const DenoiseImage& irradiance, const DenoiseImage& albedo, double albedo_floor) {
    DenoiseImage out(irradiance.width, irradiance.height);
    for (size_t i = 0; i < out.texels.size(); ++i) {
        for (int c = 0; c < 3; ++c)
            out.texels[i][c] = irradiance.texels[i][c] * divisor(albedo.texels[i][c], albedo_floor);
    }
    return out;
}

FireflyResult firefly_clamp(const DenoiseImage& irradiance, const DenoiseImage& moments, const DenoiseImage& albedo,
                            const DenoiseImage& position, double k_sigma, double albedo_floor, uint32_t min_history) {
    const uint32_t w = irradiance.width, h = irradiance.height;
    FireflyResult out{DenoiseImage(w, h), DenoiseImage(w, h), DenoiseImage(w, h)};
    auto covered = [&](int x, int y) { return position.inside(x, y) && position.at(x, y)[3] > 0.5; };
    auto divisors = [&](int x, int y) {
        std::array<double, 3> d;
        for (int k = 0; k < 3; ++k) d[k] = divisor(albedo.at(x, y)[k], albedo_floor);
        return d;
    };
    for (int y = 0; y < int(h); ++y) {
        for (int x = 0; x < int(w); ++x) {
            if (!covered(x, y)) continue;
            std::vector<double> neighbours;
            for (int dy = -2; dy <= 2; ++dy) {
                for (int dx = -2; dx <= 2; ++dx) {
                    if ((dx == 0 && dy == 0) || !covered(x + dx, y + dy)) continue;
                    neighbours.push_back(luminance(irradiance.at(x + dx, y + dy)));
                }
            }
            const auto d = divisors(x, y);
            Texel4 c = irradiance.at(x, y);
            const double l = luminance(c);
            if (neighbours.size() >= 4) {
                double mean = 0.0;
                for (double v : neighbours) mean += v;
                mean /= double(neighbours.size());
                double variance = 0.0;  // two-pass: the plain definition
                for (double v : neighbours) variance += (v - mean) * (v - mean);
                variance /= double(neighbours.size());
                double limit = mean + k_sigma * std::sqrt(variance);
                const Texel4& m = moments.at(x, y);
                if (m[2] >= min_history)
                    limit = std::max(limit, l - k_sigma * std::sqrt(std::max(m[1] - m[0] * m[0], 0.0) / m[2]));
                if (l > limit) {
                    for (int k = 0; k < 3; ++k) {
                        const double kept = c[k] * limit / l;
                        out.excess.at(x, y)[k] = (c[k] - kept) * d[k] / double(neighbours.size());
                        c[k] = kept;
                    }
                    out.excess.at(x, y)[3] = l - limit;
                }
            }
            out.clamped.at(x, y) = c;
        }
    }
    // Each covered pixel gathers its covered neighbours' shares of radiance (the neighbour
    // relation is symmetric, so every share lands once) and turns them into its own irradiance.
    for (int y = 0; y < int(h); ++y) {
        for (int x = 0; x < int(w); ++x) {
            if (!covered(x, y)) continue;
            const auto d = divisors(x, y);
            Texel4 c = out.clamped.at(x, y);
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx)
                    if ((dx != 0 || dy != 0) && covered(x + dx, y + dy))
                        for (int k = 0; k < 3; ++k) c[k] += out.excess.at(x + dx, y + dy)[k] / d[k];
            out.spread.at(x, y) = c;
        }
    }
    return out;
}

bool reproject(const std::array<double, 16>& m, const std::array<double, 3>& p, uint32_t width, uint32_t height,
               double& x, double& y) {
    // Column-major: clip_r = sum_c m[c * 4 + r] p_c (p_3 = 1).
    double clip[4];
    for (int r = 0; r < 4; ++r) clip[r] = m[0 * 4 + r] * p[0] + m[1 * 4 + r] * p[1] + m[2 * 4 + r] * p[2] + m[12 + r];
    if (!(clip[3] > 0.0)) return false;
    x = (clip[0] / clip[3] * 0.5 + 0.5) * width - 0.5;
    y = (clip[1] / clip[3] * 0.5 + 0.5) * height - 0.5;
    return true;
}

TemporalResult temporal_accumulate(const DenoiseImage& irradiance, const DenoiseGeometry& current,
                                   const DenoiseGeometry& previous, const DenoiseImage& previous_color,
                                   const DenoiseImage& previous_moments, const TemporalParameters& parameters) {
    const uint32_t w = irradiance.width, h = irradiance.height;
    TemporalResult result{DenoiseImage(w, h), DenoiseImage(w, h)};
    for (int y = 0; y < int(h); ++y) {
        for (int x = 0; x < int(w); ++x) {
            if (!current.covered(x, y)) continue;
            const Vec3d p = xyz(current.position.at(x, y));
            const Vec3d n = xyz(current.normal.at(x, y));
            const Texel4& c = irradiance.at(x, y);
            const double l = luminance(c);
            double color[3] = {c[0], c[1], c[2]};
            double m1 = l, m2 = l * l, count = 1.0;
            double hx = 0.0, hy = 0.0;
            bool still = false;
            if (parameters.has_history && reproject(parameters.previous_view_projection, p, w, h, hx, hy)) {
                still = std::abs(hx - x) <= parameters.static_pixels && std::abs(hy - y) <= parameters.static_pixels;
                if (still) hx = x, hy = y;
                const int bx = int(std::floor(hx)), by = int(std::floor(hy));
                const double fx = hx - bx, fy = hy - by;
                double hc[3] = {0, 0, 0}, hm[3] = {0, 0, 0}, weights = 0.0;
                for (int oy = 0; oy <= 1; ++oy) {
                    for (int ox = 0; ox <= 1; ++ox) {
                        const int qx = bx + ox, qy = by + oy;
                        const double bilinear = (ox ? fx : 1.0 - fx) * (oy ? fy : 1.0 - fy);
                        if (bilinear <= 0.0 || !previous.covered(qx, qy)) continue;
                        const Vec3d pq = xyz(previous.position.at(qx, qy));
                        if (std::abs(dot3(n, sub(pq, p))) > parameters.max_plane_distance ||
                            dot3(n, xyz(previous.normal.at(qx, qy))) < parameters.min_normal_cos) {
                            continue;
                        }
                        for (int k = 0; k < 3; ++k) {
                            hc[k] += bilinear * previous_color.at(qx, qy)[k];
                            hm[k] += bilinear * previous_moments.at(qx, qy)[k];
                        }
                        weights += bilinear;
                    }
                }
                if (weights > 0.01) {
                    count = std::floor(hm[2] / weights + 0.5) + 1.0;
                    const uint32_t cap = still ? parameters.static_max_history : parameters.max_history;
                    if (cap != 0) count = std::min(count, double(cap));
                    const double alpha = 1.0 / count;
                    for (int k = 0; k < 3; ++k) color[k] = (1.0 - alpha) * hc[k] / weights + alpha * color[k];
                    m1 = (1.0 - alpha) * hm[0] / weights + alpha * m1;
                    m2 = (1.0 - alpha) * hm[1] / weights + alpha * m2;
                }
            }
            result.accumulated.at(x, y) = {color[0], color[1], color[2], std::max(m2 - m1 * m1, 0.0)};
            result.moments.at(x, y) = {m1, m2, count, 0.0};
        }
    }
    return result;
}

DenoiseImage variance_estimate(const DenoiseImage& accumulated, const DenoiseImage& moments,
                               const DenoiseGeometry& geometry, const FilterParameters& parameters) {
    DenoiseImage out = accumulated;
    for (int y = 0; y < int(out.height); ++y) {
        for (int x = 0; x < int(out.width); ++x) {
            if (!geometry.covered(x, y) || moments.at(x, y)[2] >= parameters.min_history) continue;
            const Vec3d p = xyz(geometry.position.at(x, y));
            const Vec3d n = xyz(geometry.normal.at(x, y));
            double s1 = 0.0, s2 = 0.0, weights = 0.0;
            for (int dy = -3; dy <= 3; ++dy) {
                for (int dx = -3; dx <= 3; ++dx) {
                    if (!geometry.covered(x + dx, y + dy)) continue;
                    const double wq =
                        plane_weight(p, n, xyz(geometry.position.at(x + dx, y + dy)), parameters.sigma_plane) *
                        normal_weight(n, xyz(geometry.normal.at(x + dx, y + dy)), parameters.sigma_normal);
                    s1 += wq * moments.at(x + dx, y + dy)[0];
                    s2 += wq * moments.at(x + dx, y + dy)[1];
                    weights += wq;
                }
            }
            s1 /= weights;
            s2 /= weights;
            out.at(x, y)[3] = std::max(s2 - s1 * s1, 0.0);
        }
    }
    return out;
}

// atrous_variance.comp, atrous_weights.comp and atrous.comp: symmetric edge weights w(p, q),
// a(p, q) = h w / max(W_p, W_q) off the centre and a(p, p) = 1 - their sum.
DenoiseImage atrous(const DenoiseImage& source, const DenoiseGeometry& geometry, int step,
                    const FilterParameters& parameters) {
    const int width = int(source.width), height = int(source.height);
    const double h[3] = {3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0};
    std::vector<double> blurred(source.texels.size(), 0.0), sums(source.texels.size(), 0.0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (!geometry.covered(x, y)) continue;
            double g_sum = 0.0, g_weights = 0.0;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    if (!geometry.covered(x + dx, y + dy)) continue;
                    const double g = (2 - std::abs(dx)) * (2 - std::abs(dy));
                    g_sum += g * source.at(x + dx, y + dy)[3];
                    g_weights += g;
                }
            }
            blurred[size_t(y) * width + x] = g_sum / g_weights;
        }
    }
    // w(p, q) h(q) for the tap (dx, dy) of (x, y), or 0 where it is not covered or is the centre.
    auto tap_weight = [&](int x, int y, int dx, int dy) {
        const int qx = x + step * dx, qy = y + step * dy;
        if ((dx == 0 && dy == 0) || !geometry.covered(qx, qy)) return 0.0;
        const Vec3d p = xyz(geometry.position.at(x, y)), q = xyz(geometry.position.at(qx, qy));
        const Vec3d n_p = xyz(geometry.normal.at(x, y)), n_q = xyz(geometry.normal.at(qx, qy));
        const double plane = std::exp(-std::max(std::abs(dot3(n_p, sub(q, p))), std::abs(dot3(n_q, sub(p, q)))) /
                                      parameters.sigma_plane);
        const double variance =
            std::max(std::max(blurred[size_t(y) * width + x], blurred[size_t(qy) * width + qx]), 0.0);
        const double scale = parameters.sigma_luminance * std::sqrt(variance) + 1e-10;
        const double dl = std::abs(luminance(source.at(x, y)) - luminance(source.at(qx, qy)));
        return h[std::abs(dx)] * h[std::abs(dy)] * plane * normal_weight(n_p, n_q, parameters.sigma_normal) *
               std::exp(-dl / scale);
    };
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (!geometry.covered(x, y)) continue;
            double sum = h[0] * h[0];
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx) sum += tap_weight(x, y, dx, dy);
            sums[size_t(y) * width + x] = sum;
        }
    }
    DenoiseImage out(source.width, source.height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (!geometry.covered(x, y)) continue;
            double color[3] = {0, 0, 0}, variance = 0.0, given = 0.0;
            for (int dy = -2; dy <= 2; ++dy) {
                for (int dx = -2; dx <= 2; ++dx) {
                    const double w = tap_weight(x, y, dx, dy);
                    if (w == 0.0) continue;
                    const int qx = x + step * dx, qy = y + step * dy;
                    const double a = w / std::max(sums[size_t(y) * width + x], sums[size_t(qy) * width + qx]);
                    const Texel4& s = source.at(qx, qy);
                    for (int k = 0; k < 3; ++k) color[k] += a * s[k];
                    variance += a * a * s[3];
                    given += a;
                }
            }
            const double kept = std::max(1.0 - given, 0.0);
            const Texel4& c = source.at(x, y);
            out.at(x, y) = {color[0] + kept * c[0], color[1] + kept * c[1], color[2] + kept * c[2],
                            variance + kept * kept * c[3]};
        }
    }
    return out;
}

}  // namespace vplkit::reference
