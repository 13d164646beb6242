// The child probabilities of the RTSLC traversal (rtslc_child_probability, the RTSLC paper eqs. 1-2)
// and the cut bound (rtslc_node_bound), run by a test shader (shaders/rtslc_probabilities.comp)
// on random node pairs and on the hard cases: shading point inside one box, inside both, on a
// VPL, a child of zero weight (black, bogus, behind the surface), both zero (dead branch), HDR
// intensities, scenes at 1e-3 and 1e4 scale.
//
// Checks: p_left + p_right = 1 (exactly: p_left is a multiple of 2^-24), both finite and in
// [0, 1]; a zero-weight child gets exactly 0; a dead branch is flagged; a positive-weight child
// never gets 0; p_left matches the double reference within 2e-4 absolute. Why 2e-4: p is a ratio
// of weights whose float errors are those of the BRDF (up to 2e-4 relative at the GGX peak, see
// tests/gi/test_exact_gi.cpp) and of the cosine bound (~1e-6), and dp <= p (1 - p) (da_l / a_l +
// da_r / a_r) <= 1e-4, plus the rounding up to 2^-24. Bounds: relative 5e-4 (same errors, not
// halved by a ratio).

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/rtslc_test/rtslc_probabilities.hpp"
#include "vplkit_test/context.hpp"
#include "rtslc_reference.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

namespace ref = vplkit::reference;
namespace shader = vplkit::rtslc_test::rtslc_probabilities;
using Case = vplkit::rtslc_test::RtslcProbabilityCase;
using Result = vplkit::rtslc_test::RtslcProbabilityResult;
using Node = vplkit::rtslc_test::LightTreeNode;

constexpr float kFloatMax = 3.402823466e+38f;

struct Box {
    float lo[3], hi[3];
};

Node real_node(const Box& b, float intensity, uint32_t count = 2) {
    Node n{};
    n.box_min = {b.lo[0], b.lo[1], b.lo[2]};
    n.box_max = {b.hi[0], b.hi[1], b.hi[2]};
    n.intensity = intensity;
    n.vpl_count = count;
    return n;
}

Node bogus_node() {
    Node n{};
    n.box_min = {kFloatMax, kFloatMax, kFloatMax};
    n.box_max = {-kFloatMax, -kFloatMax, -kFloatMax};
    return n;
}

ref::RtslcNode to_ref(const Node& n) {
    return {{n.box_min.x, n.box_min.y, n.box_min.z}, {n.box_max.x, n.box_max.y, n.box_max.z}, n.intensity, n.vpl_count};
}

struct Named {
    Case c;
    std::string kind;
};

struct Generator {
    std::mt19937 rng{17};
    std::uniform_real_distribution<float> unit{0.0f, 1.0f};

    float range(float a, float b) { return a + (b - a) * unit(rng); }

    void unit_vector(float v[3], float min_y) {
        for (;;) {
            float x = range(-1, 1), y = range(min_y, 1), z = range(-1, 1);
            const float l = std::sqrt(x * x + y * y + z * z);
            if (l > 0.2f && l <= 1.0f) {
                v[0] = x / l;
                v[1] = y / l;
                v[2] = z / l;
                return;
            }
        }
    }

    // A shading point at the origin scaled by `scale`, normal near +y, a random material.
    Case shading(float scale) {
        Case c{};
        float n[3], jitter[3];
        unit_vector(n, 0.3f);
        unit_vector(jitter, -1.0f);
        // Towards the viewer: within ~50 degrees of the normal, so always on its side.
        float wo[3] = {n[0] + 0.8f * jitter[0], n[1] + 0.8f * jitter[1], n[2] + 0.8f * jitter[2]};
        const float lw = std::sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
        c.position = {range(-0.1f, 0.1f) * scale, range(-0.1f, 0.1f) * scale, range(-0.1f, 0.1f) * scale};
        c.normal = {n[0], n[1], n[2]};
        c.wo = {wo[0] / lw, wo[1] / lw, wo[2] / lw};
        c.base_color = {unit(rng), unit(rng), unit(rng)};
        c.roughness = range(0.25f, 1.0f);
        c.metallic = unit(rng) < 0.3f ? 1.0f : 0.0f;
        const float eps = 1e-2f * 3.0f * scale;  // vpl_min_distance of a scene of size 3 scale
        c.min_distance2 = eps * eps;
        return c;
    }

    // A box of size up to `extent` around a centre within `spread` of the origin.
    Box box(float scale, float spread, float extent) {
        Box b;
        for (int k = 0; k < 3; ++k) {
            const float centre = range(-spread, spread) * scale;
            const float half = range(0.0f, extent) * scale;
            b.lo[k] = centre - half;
            b.hi[k] = centre + half;
        }
        return b;
    }

    Box around(const Case& c, float scale, float extent) {
        Box b;
        const float p[3] = {c.position.x, c.position.y, c.position.z};
        for (int k = 0; k < 3; ++k) {
            b.lo[k] = p[k] - range(0.01f, extent) * scale;
            b.hi[k] = p[k] + range(0.01f, extent) * scale;
        }
        return b;
    }

    float intensity(float decades_lo = -1.0f, float decades_hi = 1.0f) {
        return std::pow(10.0f, range(decades_lo, decades_hi));
    }
};

std::vector<Named> make_cases() {
    Generator g;
    std::vector<Named> out;
    for (float scale : {1.0f, 1e-3f, 1e4f}) {
        const float flux = scale * scale;  // radiance-invariant flux at this scale
        for (int i = 0; i < 300; ++i) {
            Case c = g.shading(scale);
            c.left = real_node(g.box(scale, 3.0f, 1.0f), g.intensity() * flux);
            c.right = real_node(g.box(scale, 3.0f, 1.0f), g.intensity() * flux);
            out.push_back({c, "random"});
        }
        for (int i = 0; i < 40; ++i) {
            Case c = g.shading(scale);
            c.left = real_node(g.around(c, scale, 0.5f), g.intensity() * flux);
            c.right = real_node(g.box(scale, 3.0f, 0.5f), g.intensity() * flux);
            if (i % 2) std::swap(c.left, c.right);
            out.push_back({c, "inside one box"});
        }
        for (int i = 0; i < 40; ++i) {
            Case c = g.shading(scale);
            c.left = real_node(g.around(c, scale, 0.5f), g.intensity() * flux);
            c.right = real_node(g.around(c, scale, 1.5f), g.intensity() * flux);
            out.push_back({c, "inside both boxes"});
        }
        for (int i = 0; i < 20; ++i) {
            // The left child is one VPL exactly at the shading point: no direction, weight 0.
            Case c = g.shading(scale);
            const Box on{{c.position.x, c.position.y, c.position.z}, {c.position.x, c.position.y, c.position.z}};
            c.left = real_node(on, g.intensity() * flux, 1);
            c.right = real_node(g.box(scale, 3.0f, 1.0f), g.intensity() * flux);
            out.push_back({c, "on a VPL"});
        }
        for (int i = 0; i < 60; ++i) {
            Case c = g.shading(scale);
            c.left = real_node(g.box(scale, 3.0f, 1.0f), g.intensity() * flux);
            const int which = i % 3;
            if (which == 0) {
                c.right = real_node(g.box(scale, 3.0f, 1.0f), 0.0f);  // black flux
            } else if (which == 1) {
                c.right = bogus_node();
            } else {
                // Wholly behind the surface: every corner 0.5..1.5 below the tangent plane.
                Box b = g.box(scale, 0.3f, 0.2f);
                const float n[3] = {c.normal.x, c.normal.y, c.normal.z};
                for (int k = 0; k < 3; ++k) {
                    b.lo[k] -= 1.5f * scale * n[k] + 0.25f * scale;
                    b.hi[k] -= 1.5f * scale * n[k] - 0.25f * scale;
                    b.hi[k] = std::max(b.hi[k], b.lo[k]);
                }
                c.right = real_node(b, g.intensity() * flux);
            }
            if (i % 2) std::swap(c.left, c.right);
            out.push_back({c, "zero-weight child"});
        }
        for (int i = 0; i < 20; ++i) {
            Case c = g.shading(scale);
            c.left = real_node(g.box(scale, 3.0f, 1.0f), 0.0f);
            c.right = i % 2 ? bogus_node() : real_node(g.box(scale, 3.0f, 1.0f), 0.0f);
            out.push_back({c, "dead branch"});
        }
        for (int i = 0; i < 60; ++i) {
            Case c = g.shading(scale);
            c.left = real_node(g.box(scale, 3.0f, 1.0f), g.intensity(-6.0f, 6.0f) * flux);
            c.right = real_node(g.box(scale, 3.0f, 1.0f), g.intensity(-6.0f, 6.0f) * flux);
            out.push_back({c, "HDR"});
        }
    }
    return out;
}

std::vector<Result> run(const std::vector<Named>& named) {
    vplkit::Context& ctx = vplkit::test::context();
    std::vector<Case> cases;
    for (const Named& n : named) cases.push_back(n.c);
    const auto count = uint32_t(cases.size());
    auto input = vplkit::Buffer::create(ctx, count * sizeof(Case), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vplkit::MemoryUse::device, "cases");
    auto output = vplkit::Buffer::create(ctx, count * sizeof(Result), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vplkit::MemoryUse::device, "results");
    input.upload(cases);
    const auto& pipeline = ctx.pipeline<shader::Pipeline>();
    vplkit::PassList passes("rtslc probabilities test");
    passes.add("rtslc probabilities", {vplkit::Use::read(input), vplkit::Use::write(output)}, [&](VkCommandBuffer cmd) {
        shader::Bindings b;
        b.cases = input.descriptor();
        b.results = output.descriptor();
        shader::Push push{};
        push.count = count;
        pipeline.dispatch(cmd, b, push, count);
    });
    passes.run(ctx);
    return output.download<Result>(count);
}

ref::RtslcShading ref_shading(const Case& c) {
    ref::RtslcShading s;
    s.position = {c.position.x, c.position.y, c.position.z};
    s.normal = {c.normal.x, c.normal.y, c.normal.z};
    s.wo = {c.wo.x, c.wo.y, c.wo.z};
    s.base_color = {c.base_color.x, c.base_color.y, c.base_color.z};
    s.roughness = c.roughness;
    s.metallic = c.metallic;
    return s;
}

}  // namespace

TEST_CASE("rtslc probabilities: children sum to one and match the double reference") {
    const auto cases = make_cases();
    const auto results = run(cases);
    double largest_error = 0.0;
    int zero_children = 0, dead = 0, inside = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        const Case& c = cases[i].c;
        const Result& r = results[i];
        CAPTURE(i);
        CAPTURE(cases[i].kind);
        REQUIRE(std::isfinite(r.p_left));
        REQUIRE(std::isfinite(r.p_right));
        REQUIRE(std::isfinite(r.bound_left));
        REQUIRE(std::isfinite(r.bound_right));
        const ref::RtslcShading s = ref_shading(c);
        const double eps = std::sqrt(double(c.min_distance2));
        const auto expected = ref::rtslc_child_probability(s, to_ref(c.left), to_ref(c.right), eps);
        CHECK((r.dead == 1) == expected.dead);
        if (cases[i].kind == "dead branch") {
            CHECK(r.dead == 1);
            ++dead;
        }
        if (expected.dead) continue;
        // Both are multiples of 2^-24 in [0, 1]: the sum is exact.
        CHECK(r.p_left >= 0.0f);
        CHECK(r.p_right >= 0.0f);
        CHECK(std::abs(double(r.p_left) + double(r.p_right) - 1.0) <= 1e-6);
        CHECK(double(r.p_left) + double(r.p_right) == 1.0);
        const double a_left = ref::rtslc_node_importance(s, to_ref(c.left));
        const double a_right = ref::rtslc_node_importance(s, to_ref(c.right));
        if (a_left == 0.0) {
            CHECK(r.p_left == 0.0f);
            ++zero_children;
        } else {
            CHECK(r.p_left > 0.0f);
        }
        if (a_right == 0.0) {
            CHECK(r.p_right == 0.0f);
            ++zero_children;
        } else {
            CHECK(r.p_right > 0.0f);
        }
        const double error = std::abs(double(r.p_left) - expected.left);
        largest_error = std::max(largest_error, error);
        CHECK(error <= 2e-4);
        inside += cases[i].kind == "inside both boxes";
        for (auto [gpu, node] : {std::pair{r.bound_left, c.left}, std::pair{r.bound_right, c.right}}) {
            const double bound = ref::rtslc_node_bound(s, to_ref(node), eps);
            CHECK(double(gpu) == doctest::Approx(bound).epsilon(5e-4));
        }
    }
    MESSAGE("largest |p_left - reference|: " << largest_error);
    CHECK(zero_children >= 3 * 60);  // every zero-weight case (and the points on a VPL)
    CHECK(dead == 3 * 20);
    CHECK(inside == 3 * 40);
}

TEST_CASE("rtslc probabilities: a shading point on a VPL or inside both boxes") {
    // Inside both boxes (and on a VPL) the clamped d_min^2 are both eps^2: p_min is the ratio of
    // F I alone (the paper's "ignore the distance terms"). Two identical boxes around x with
    // intensities 1 and 3 and a diffuse material: d_max^2 are equal too, so p = F_l / (F_l + 3 F_r)
    // with F_l = F_r (same box, same centre): exactly 1/4.
    Generator g;
    Case c = g.shading(1.0f);
    c.metallic = 0.0f;
    const Box b = g.around(c, 1.0f, 0.5f);
    c.left = real_node(b, 1.0f);
    c.right = real_node(b, 3.0f);
    // A VPL exactly at x (left) beside a cluster far away: the point box has no direction from x,
    // so its cosine bound and weight are 0 (vpl_geometry gives it 0 too) and it is never chosen.
    Case on = g.shading(1.0f);
    const Box point{{on.position.x, on.position.y, on.position.z}, {on.position.x, on.position.y, on.position.z}};
    on.left = real_node(point, 5.0f, 1);
    on.right = real_node(g.box(1.0f, 3.0f, 0.2f), 1e-3f);
    const auto results = run({{c, "inside both"}, {on, "on a VPL"}});
    CHECK(results[0].p_left == 0.25f);
    CHECK(results[0].p_right == 0.75f);
    CHECK(results[0].dead == 0);
    CHECK(results[1].p_left == 0.0f);
    CHECK(results[1].p_right == 1.0f);
    CHECK(results[1].bound_left == 0.0f);
}
