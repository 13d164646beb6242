#include "bvh_test_support.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace vplkit::bvh_test {

namespace {

using shaders::BvhHit;
using shaders::BvhRay;

glm::vec3 to_glm(const shaders::vec3& v) {
    return {v.x, v.y, v.z};
}
reference::Double3 to_double(const glm::vec3& v) {
    return {v.x, v.y, v.z};
}

void add_triangle(Triangles& out, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    out.push_back(a);
    out.push_back(b);
    out.push_back(c);
}

}  // namespace

Triangles random_soup(uint32_t count, uint32_t seed, float size) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    Triangles out;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 centre(unit(rng), unit(rng), unit(rng));
        for (int k = 0; k < 3; ++k) {
            out.push_back(centre + 0.5f * size * glm::vec3(unit(rng), unit(rng), unit(rng)));
        }
    }
    return out;
}

Triangles icosphere(uint32_t levels) {
    const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> vertices = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                                       {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    for (auto& v : vertices) {
        v = glm::normalize(v);
    }
    std::vector<std::array<uint32_t, 3>> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                                  {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                  {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                                  {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (uint32_t level = 0; level < levels; ++level) {
        // Shared midpoints, so that neighbouring faces use the very same float vertex.
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            auto [it, inserted] = midpoints.try_emplace(key, uint32_t(vertices.size()));
            if (inserted) {
                vertices.push_back(glm::normalize(vertices[a] + vertices[b]));
            }
            return it->second;
        };
        std::vector<std::array<uint32_t, 3>> next;
        for (const auto& f : faces) {
            const uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            next.push_back({f[0], ab, ca});
            next.push_back({f[1], bc, ab});
            next.push_back({f[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        faces = std::move(next);
    }
    Triangles out;
    for (const auto& f : faces) {
        add_triangle(out, vertices[f[0]], vertices[f[1]], vertices[f[2]]);
    }
    return out;
}

Triangles grid_box(uint32_t n) {
    Triangles out;
    const float step = 2.0f / float(n);
    // Each face: axis `a` fixed at side s; u, v the other two axes in an order that makes the
    // winding counter-clockwise seen from outside.
    for (int a = 0; a < 3; ++a) {
        for (float s : {-1.0f, 1.0f}) {
            int u = (a + 1) % 3, v = (a + 2) % 3;
            if (s < 0) {
                std::swap(u, v);
            }
            auto point = [&](uint32_t i, uint32_t j) {
                glm::vec3 p;
                p[a] = s;
                p[u] = -1.0f + step * float(i);
                p[v] = -1.0f + step * float(j);
                return p;
            };
            for (uint32_t i = 0; i < n; ++i) {
                for (uint32_t j = 0; j < n; ++j) {
                    // Alternate the diagonal, so vertices join 4 or 8 triangles.
                    if ((i + j) % 2 == 0) {
                        add_triangle(out, point(i, j), point(i + 1, j), point(i + 1, j + 1));
                        add_triangle(out, point(i, j), point(i + 1, j + 1), point(i, j + 1));
                    } else {
                        add_triangle(out, point(i, j), point(i + 1, j), point(i, j + 1));
                        add_triangle(out, point(i + 1, j), point(i + 1, j + 1), point(i, j + 1));
                    }
                }
            }
        }
    }
    return out;
}

Triangles transformed(const Triangles& triangles, float scale, glm::vec3 offset) {
    Triangles out;
    out.reserve(triangles.size());
    for (const auto& v : triangles) {
        out.push_back(v * scale + offset);
    }
    return out;
}

std::vector<reference::Triangle> to_reference(const Triangles& triangles) {
    std::vector<reference::Triangle> out;
    for (size_t i = 0; i + 2 < triangles.size(); i += 3) {
        out.push_back({to_double(triangles[i]), to_double(triangles[i + 1]), to_double(triangles[i + 2])});
    }
    return out;
}

reference::Ray to_reference(const BvhRay& ray) {
    return {to_double(to_glm(ray.origin)), to_double(to_glm(ray.direction)), ray.tmin, ray.tmax};
}

BvhRay make_ray(glm::vec3 origin, glm::vec3 direction, float tmin, float tmax) {
    BvhRay ray{};
    ray.origin = {origin.x, origin.y, origin.z};
    ray.direction = {direction.x, direction.y, direction.z};
    ray.tmin = tmin;
    ray.tmax = tmax;
    return ray;
}

glm::vec3 random_direction(std::mt19937& rng) {
    std::normal_distribution<float> gauss;
    for (;;) {
        glm::vec3 d(gauss(rng), gauss(rng), gauss(rng));
        const float length = glm::length(d);
        if (length > 1e-3f) {
            return d / length;
        }
    }
}

std::vector<BvhHit> trace_closest(const stages::BvhBuffers& bvh, std::span<const BvhRay> rays) {
    Context& ctx = test::context();
    const uint32_t count = uint32_t(rays.size());
    auto ray_buffer =
        Buffer::create(ctx, rays.size_bytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "rays");
    auto hit_buffer =
        Buffer::create(ctx, count * sizeof(BvhHit), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "hits");
    ray_buffer.upload(rays);
    PassList passes("bvh test closest");
    add_trace_rays_pass(ctx, passes, bvh, ray_buffer, hit_buffer, count, TraceMode::closest_hit);
    passes.run(ctx);
    return hit_buffer.download<BvhHit>(count);
}

std::vector<uint32_t> trace_occlusion(const stages::BvhBuffers& bvh, std::span<const BvhRay> rays) {
    Context& ctx = test::context();
    const uint32_t count = uint32_t(rays.size());
    auto ray_buffer =
        Buffer::create(ctx, rays.size_bytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "rays");
    auto result_buffer = Buffer::create(ctx, count * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        MemoryUse::device, "occlusion");
    ray_buffer.upload(rays);
    PassList passes("bvh test occlusion");
    add_trace_rays_pass(ctx, passes, bvh, ray_buffer, result_buffer, count, TraceMode::occlusion);
    passes.run(ctx);
    return result_buffer.download<uint32_t>(count);
}

Agreement compare_with_reference(std::span<const reference::Triangle> triangles, std::span<const BvhRay> rays,
                                 std::span<const BvhHit> hits, std::span<const uint32_t> occlusion) {
    Agreement result;
    result.rays = rays.size();
    for (size_t r = 0; r < rays.size(); ++r) {
        const reference::Ray ray = to_reference(rays[r]);
        const double dlen = reference::length(ray.direction);
        // Every triangle the ray certainly hits (inside by more than the edge rounding, t inside
        // (tmin, tmax) by more than the t rounding), and every one it may hit in float.
        double certain_t = std::numeric_limits<double>::infinity();
        bool any_certain = false, any_possible = false;
        for (size_t i = 0; i < triangles.size(); ++i) {
            const auto h = reference::intersect(ray, triangles[i]);
            if (!h) {
                continue;
            }
            const double reach = reference::farthest_vertex(triangles[i], ray.origin);
            const double t_tol = kRelativeTolerance * std::max(std::fabs(h->t), reach / dlen);
            const double a = reference::area(triangles[i]);
            const double edge_tol = kRelativeTolerance * std::max(1.0, reach * reach / (2.0 * a));
            if (h->margin >= edge_tol && h->t > ray.tmin + t_tol && h->t < ray.tmax - t_tol) {
                any_certain = true;
                certain_t = std::min(certain_t, h->t);
            }
            if (h->margin >= -edge_tol && h->t > ray.tmin - t_tol && h->t < ray.tmax + t_tol) {
                any_possible = true;
            }
        }
        const reference::ClosestHit ref = reference::closest_hit(triangles, ray);
        result.hits += ref.hit ? 1 : 0;
        const BvhHit& gpu = hits[r];
        bool excused = false;
        auto fail = [&](const char* what) {
            ++result.failures;
            if (result.failures <= 5) {
                MESSAGE("ray " << r << " o=(" << ray.origin[0] << ", " << ray.origin[1] << ", " << ray.origin[2]
                               << ") d=(" << ray.direction[0] << ", " << ray.direction[1] << ", " << ray.direction[2]
                               << ") [" << ray.tmin << ", " << ray.tmax << "]: " << what << "; gpu id " << gpu.id
                               << " t " << gpu.t << ", reference " << (ref.hit ? "hit " : "miss ") << ref.triangle
                               << " t " << ref.t);
            }
        };

        if (gpu.id == kBvhNoHit) {
            if (any_certain) {
                fail("missed a certain hit");
            } else if (ref.hit) {
                excused = true;
            }
            const float tmax = std::isinf(rays[r].tmax) ? std::numeric_limits<float>::max() : rays[r].tmax;
            if (gpu.t != tmax) {
                fail("a miss must report t = tmax");
            }
        } else if (gpu.id >= triangles.size()) {
            fail("id out of range");
        } else {
            const auto h = reference::intersect(ray, triangles[gpu.id]);
            const double reach = reference::farthest_vertex(triangles[gpu.id], ray.origin);
            const double t_tol = kRelativeTolerance * std::max(h ? std::fabs(h->t) : 0.0, reach / dlen);
            const double edge_tol =
                kRelativeTolerance * std::max(1.0, reach * reach / (2.0 * reference::area(triangles[gpu.id])));
            if (!h || h->margin < -edge_tol || !(h->t > ray.tmin - t_tol && h->t < ray.tmax + t_tol)) {
                fail("hit a triangle the ray does not meet");
            } else {
                if (std::fabs(double(gpu.t) - h->t) > t_tol) {
                    fail("t differs from the reference t of the same triangle");
                }
                if (std::fabs(double(gpu.barycentrics.x) - h->b1) > edge_tol ||
                    std::fabs(double(gpu.barycentrics.y) - h->b2) > edge_tol) {
                    fail("barycentrics differ from the reference");
                }
                if (any_certain && h->t > certain_t + t_tol) {
                    fail("a certain hit lies nearer than the one found");
                }
                if (!ref.hit) {
                    excused = true;
                } else if (gpu.id != ref.triangle) {
                    if (std::fabs(h->t - ref.t) <= t_tol) {
                        ++result.ties;
                    } else {
                        excused = true;
                    }
                }
            }
        }

        const bool ref_occluded = reference::occluded(triangles, ray);
        const bool gpu_occluded = occlusion[r] != 0;
        if (occlusion[r] > 1) {
            fail("occlusion is neither 0 nor 1");
        }
        if (any_certain && !gpu_occluded) {
            fail("occlusion missed a certain hit");
        } else if (!any_possible && gpu_occluded) {
            fail("occluded where nothing can be hit");
        } else if (gpu_occluded != ref_occluded) {
            ++result.occlusion_near;
        }
        result.near_edge += excused ? 1 : 0;
    }
    return result;
}

Agreement check_against_reference(const Triangles& triangles, std::span<const BvhRay> rays, double max_excused_fraction,
                                  const BvhBuildOptions& options) {
    const Bvh bvh = build_bvh(triangles, {}, options);
    const GpuBvh gpu = upload_bvh(test::context(), bvh);
    const auto hits = trace_closest(gpu, rays);
    const auto occlusion = trace_occlusion(gpu, rays);
    const auto reference_triangles = to_reference(triangles);
    const Agreement result = compare_with_reference(reference_triangles, rays, hits, occlusion);
    MESSAGE(result.rays << " rays, " << result.hits << " reference hits, " << result.ties << " ties, "
                        << result.near_edge << " + " << result.occlusion_near << " excused near an edge or bound");
    CHECK(result.failures == 0);
    CHECK(double(result.near_edge) <= max_excused_fraction * double(result.rays));
    CHECK(double(result.occlusion_near) <= max_excused_fraction * double(result.rays));
    return result;
}

}  // namespace vplkit::bvh_test
