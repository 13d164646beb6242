#include "scene/gltf_animation_sampler.hpp"

#include <algorithm>
#include <cmath>

namespace vplkit::scene::detail {
namespace {

// Key k's value (the middle of the three CUBICSPLINE elements), `components` wide.
const double* key_value(const KeyedChannel& c, size_t k) {
    return c.interpolation == Interpolation::cubic_spline ? &c.values[(3 * k + 1) * c.components]
                                                          : &c.values[k * c.components];
}

void normalize(std::vector<double>& q) {
    double length = 0.0;
    for (double v : q) length += v * v;
    length = std::sqrt(length);
    if (length > 0.0) {
        for (double& v : q) v /= length;
    }
}

// glTF 2.0 Appendix C's slerp: along the shorter arc (b negated when the quaternions are more
// than 90 degrees apart); nearly equal quaternions, whose sin(angle) would divide by ~0, are
// interpolated linearly (the result is normalized after).
std::vector<double> slerp(const double* a, const double* b, double s) {
    double d = 0.0;
    for (int i = 0; i < 4; ++i) d += a[i] * b[i];
    const double sign = d < 0.0 ? -1.0 : 1.0;
    const double angle = std::acos(std::min(std::abs(d), 1.0));
    double wa = 1.0 - s, wb = s;
    if (std::sin(angle) > 1e-9) {
        wa = std::sin(angle * (1.0 - s)) / std::sin(angle);
        wb = std::sin(angle * s) / std::sin(angle);
    }
    std::vector<double> out(4);
    for (int i = 0; i < 4; ++i) out[size_t(i)] = wa * a[i] + sign * wb * b[i];
    return out;
}

}  // namespace

std::vector<double> sample_channel(const KeyedChannel& c, double t) {
    const size_t n = c.times.size();
    const size_t w = c.components;
    auto value_of = [&](size_t k) {
        const double* v = key_value(c, k);
        std::vector<double> out(v, v + w);
        if (c.path == AnimatedPath::rotation) normalize(out);
        return out;
    };
    if (n == 1 || t <= c.times.front()) return value_of(0);
    if (t >= c.times.back()) return value_of(n - 1);
    // The key interval [t_k, t_k+1) holding t.
    const size_t k = size_t(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) - 1;
    const double dt = c.times[k + 1] - c.times[k];
    const double s = (t - c.times[k]) / dt;

    std::vector<double> out(w);
    switch (c.interpolation) {
        case Interpolation::step:
            return value_of(k);
        case Interpolation::linear: {
            const double* a = key_value(c, k);
            const double* b = key_value(c, k + 1);
            if (c.path == AnimatedPath::rotation) {
                out = slerp(a, b, s);
            } else {
                for (size_t i = 0; i < w; ++i) out[i] = (1.0 - s) * a[i] + s * b[i];
            }
            break;
        }
        case Interpolation::cubic_spline: {
            // Hermite basis on p0 = v_k, m0 = dt b_k (out-tangent), p1 = v_k+1, m1 = dt a_k+1 (in-tangent).
            const double* p0 = &c.values[(3 * k + 1) * w];
            const double* b0 = &c.values[(3 * k + 2) * w];
            const double* a1 = &c.values[(3 * (k + 1)) * w];
            const double* p1 = &c.values[(3 * (k + 1) + 1) * w];
            const double s2 = s * s, s3 = s2 * s;
            const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
            for (size_t i = 0; i < w; ++i) {
                out[i] = h00 * p0[i] + h10 * dt * b0[i] + h01 * p1[i] + h11 * dt * a1[i];
            }
            break;
        }
    }
    if (c.path == AnimatedPath::rotation) normalize(out);
    return out;
}

}  // namespace vplkit::scene::detail
