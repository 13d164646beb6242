// direct_light_tree.comp (with rtslc's cut pass and traversal) and the light tree over a scene's
// lights (light_tree_scene_leaves.comp over the VPL keys, sort and levels): the estimate's mean
// over seeds, with visibility off, against the exact direct light of every light in double
// precision (tests/reference/direct_light_reference.cpp's BRDF and punctual falloff), each
// triangle integrated by the midpoint rule on 48^2 equal sub-triangles (relative error ~1e-4
// here: the emitters are small and at least 0.4 above the floor, far below the Monte Carlo
// bound). Check, per covered pixel and channel: |mean - exact| <= 5 sigma / sqrt(seeds) +
// 2e-3 exact, sigma the spread of the per-seed estimates (DESIGN.md), for two seed counts.
// Why 64 and 256 seeds and not 16: a bright emitter under the glossy highlight (roughness 0.7) is
// a heavy tail for uniform area sampling; with 16 seeds the sample sigma underestimated it (z 5.3
// at 16 seeds, 3.2 at 64 and 2.6 at 1024 for the same scene: falling, so not a bias).
// A mismatch between the pmf a sample is divided by and the probability of the path that chose
// it, a light the weights exclude wrongly, or a cut that does not partition the lights all move
// the mean by far more than that.

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gi_counters_buffer.hpp"
#include "vplkit/gpu_light_tree.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/rtslc_scratch.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/direct_light_tree.hpp"
#include "vplkit_test/context.hpp"
#include "direct_light_reference.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "direct_light_tree_fixture.hpp"

using namespace direct_tree_fixture;

TEST_CASE("direct light tree: mean over seeds equals the exact light of 33 emitters, point and spot lights") {
    // 2^5 + 1 emitters (one bogus-padded level), radiance 1e-4..1e4, one- and double-sided, some
    // facing away, one under the floor (behind every shading point), a point light, a spot light
    // lighting the floor, a spot light whose cone misses every pixel, a directional light (not
    // the tree's), and a zero-area emitter (no power: left out of the tree).
    SceneBuilder b = many_emitters(33, 11u);
    const uint32_t under = b.add_emissive({50, 50, 50}, false);
    add_small_emitter(b, {0.2f, -0.3f, 0.1f}, 0.2f, false, under);                      // faces up, under the floor
    b.add_triangle({0.5f, 1.0f, 0.5f}, {0.5f, 1.0f, 0.5f}, {0.7f, 1.0f, 0.5f}, under);  // zero area
    b.s.lights = hard_case_punctual_lights();
    const Floor floor = make_floor();
    Harness harness(b.s, floor);
    // 33 + 1 + 1 emissive triangles, of which 34 emit; 3 point and spot lights.
    CHECK(harness.tree().triangle_count() == 34);
    CHECK(harness.tree().count() == 37);
    // Two seed counts (DESIGN.md): a z that grows with the count would be a bias.
    const double z64 = check_unbiased(b.s, harness, floor, 64, 8);
    const double z256 = check_unbiased(b.s, harness, floor, 256, 8);
    MESSAGE("largest z: " << z64 << " (64 seeds), " << z256 << " (256 seeds)");
}

TEST_CASE(
    "light tree over lights: every light in one leaf with the box of its corners and its RGB power and parents that "
    "sum their children") {
    // light_tree_scene_leaves.comp and the levels against a plain CPU reference: each leaf's light
    // (a permutation of the lights), its box (a triangle's three corners, a light's position), its
    // intensity (the RGB sum of radiance x area x pi x sides, or 4 pi I for a point light, in
    // double: float rounding of the proxy's flux, relative 1e-5), bogus leaves empty; every
    // internal node the union of its children's boxes and the sum of their intensities.
    SceneBuilder b = many_emitters(13, 3u);  // 2^3 + 5: 3 bogus leaves
    vplkit::scene::Light point;
    point.position = {0.3f, 1.1f, -0.2f};
    point.color = {1.0f, 0.5f, 0.25f};
    point.intensity = 3.0f;
    b.s.lights = {point};
    const Floor floor = make_floor();
    Harness harness(b.s, floor);
    const uint32_t count = harness.tree().count();
    REQUIRE(count == 14);
    const uint32_t leaf_count = 16;
    const auto leaves = harness.tree().leaf_lights().download<uint32_t>(count);
    const auto nodes = harness.tree().nodes().download<vplkit::shaders::LightTreeNode>(2 * leaf_count - 1);
    std::vector<bool> seen(count, false);
    for (uint32_t i = 0; i < leaf_count; ++i) {
        CAPTURE(i);
        const auto& node = nodes[leaf_count - 1 + i];
        if (i >= count) {
            CHECK(node.vpl_count == 0);
            CHECK(node.intensity == 0.0f);
            continue;
        }
        const uint32_t light = leaves[i];
        REQUIRE(light < count);
        CHECK(!seen[light]);
        seen[light] = true;
        CHECK(node.vpl_count == 1);
        glm::dvec3 lo, hi;
        double intensity = 0.0;
        if (light < 13) {
            const uint32_t t = b.s.emissive_triangles[light];
            const auto& mat = b.s.materials[b.s.triangle_materials[t]];
            const glm::dvec3 p0 = b.s.vertices[b.s.indices[3 * t]].position;
            const glm::dvec3 p1 = b.s.vertices[b.s.indices[3 * t + 1]].position;
            const glm::dvec3 p2 = b.s.vertices[b.s.indices[3 * t + 2]].position;
            lo = glm::min(glm::min(p0, p1), p2);
            hi = glm::max(glm::max(p0, p1), p2);
            const double area = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
            const glm::dvec3 e = glm::dvec3(mat.emission());
            intensity = (e.x + e.y + e.z) * area * std::numbers::pi * (mat.double_sided ? 2.0 : 1.0);
        } else {
            lo = hi = glm::dvec3(point.position);
            intensity = 4.0 * std::numbers::pi * point.intensity * (1.0 + 0.5 + 0.25);
        }
        CHECK(node.box_min.x == float(lo.x));
        CHECK(node.box_min.y == float(lo.y));
        CHECK(node.box_min.z == float(lo.z));
        CHECK(node.box_max.x == float(hi.x));
        CHECK(node.box_max.y == float(hi.y));
        CHECK(node.box_max.z == float(hi.z));
        CHECK(node.intensity == doctest::Approx(intensity).epsilon(1e-5));
    }
    for (uint32_t n = 0; n + 1 < leaf_count; ++n) {
        CAPTURE(n);
        const auto& l = nodes[2 * n + 1];
        const auto& r = nodes[2 * n + 2];
        CHECK(nodes[n].vpl_count == l.vpl_count + r.vpl_count);
        CHECK(nodes[n].intensity == l.intensity + r.intensity);  // float, left first (light_tree_merge)
        if (nodes[n].vpl_count == 0) continue;
        CHECK(nodes[n].box_min.x == std::min(l.box_min.x, r.box_min.x));
        CHECK(nodes[n].box_max.y == std::max(l.box_max.y, r.box_max.y));
        CHECK(nodes[n].box_max.z == std::max(l.box_max.z, r.box_max.z));
    }
}

TEST_CASE("direct light tree: one emitter, 2^k and 2^k + 1 emitters, a cut larger than the tree") {
    const Floor floor = make_floor();
    for (uint32_t count : {1u, 8u, 9u}) {
        CAPTURE(count);
        SceneBuilder b = many_emitters(count, 100u + count);
        Harness harness(b.s, floor);
        CHECK(harness.tree().count() == count);
        check_unbiased(b.s, harness, floor, 256, 16);  // 16 cut nodes: more than the 1, 8, 9 leaves
    }
}

TEST_CASE("direct light tree: shading points on an emitter (inside its flat box) stay finite and unbiased") {
    // A double-sided emitter lying in the floor's plane under half the pixels: their distance to
    // its box is 0 (the weights' clamp), their own light from it is 0 (grazing), and the lights
    // above still arrive.
    SceneBuilder b = many_emitters(6, 21u);
    const uint32_t m = b.add_emissive({30, 30, 30}, true);
    b.add_triangle({-1.8f, 0.0f, -1.8f}, {1.8f, 0.0f, -1.8f}, {0.0f, 0.0f, 0.2f}, m);
    const Floor floor = make_floor();
    Harness harness(b.s, floor);
    check_unbiased(b.s, harness, floor, 64, 8);
}

TEST_CASE("direct light tree: a double-sided emitter lights with its back as with its front") {
    // The same emitter wound facing up: one-sided it lights nothing below, double-sided as much
    // as wound facing down.
    const Floor floor = make_floor();
    auto render = [&](bool down, bool double_sided) {
        SceneBuilder b;
        const uint32_t m = b.add_emissive({3, 2, 1}, double_sided);
        add_small_emitter(b, {0.1f, 1.2f, -0.2f}, 0.4f, down, m);
        Harness harness(b.s, floor);
        std::vector<double> sums(3, 0.0);
        for (uint32_t seed = 0; seed < 8; ++seed) {
            const auto image = harness.run(seed, 4, true);
            for (const Texel& t : image) {
                for (int c = 0; c < 3; ++c) sums[c] += t[c];
            }
        }
        check_unbiased(b.s, harness, floor, 64, 4, down || double_sided);
        return sums;
    };
    const auto front = render(true, false);
    const auto back = render(false, true);
    const auto one_sided_up = render(false, false);
    for (int c = 0; c < 3; ++c) {
        CHECK(front[c] > 0.0);
        CHECK(back[c] == doctest::Approx(front[c]).epsilon(0.05));
        CHECK(one_sided_up[c] == 0.0);
    }
}

TEST_CASE("direct light tree: light adds to what is there and an occluder blocks it") {
    SceneBuilder b;
    const uint32_t m = b.add_emissive({4, 4, 4}, false);
    for (int i = 0; i < 12; ++i) {
        add_small_emitter(b, {-0.3f + 0.05f * i, 1.5f, -0.2f + 0.04f * i}, 0.05f, true, m);
    }
    const Floor open_floor = make_floor();
    Harness open(b.s, open_floor);
    // A plate at y = 1 over the middle hides every emitter from the floor's centre.
    b.add_quad({-0.8f, 1, -0.8f}, {-0.8f, 1, 0.8f}, {0.8f, 1, 0.8f}, {0.8f, 1, -0.8f}, 0);
    Harness covered(b.s, open_floor);
    const uint32_t centre = (kSize / 2) * kSize + kSize / 2;
    REQUIRE(open_floor.position[centre][3] == 1.0f);
    const auto lit = open.run(3, 8, true, 0.25f);
    const auto dark = covered.run(3, 8, true, 0.25f);
    CHECK(lit[centre][0] > 0.25f);
    CHECK(dark[centre][0] == 0.25f);
    CHECK(dark[centre][3] == 1.0f);  // alpha kept
    // Background pixels keep what the direct-light pass wrote.
    CHECK(lit[0][0] == 0.25f);
}

TEST_CASE("direct light tree: interleaved 2 x 2 over rotating frames gives the exact total light") {
    // Interleaving (rtslc GI's reconstruction) is an approximation per pixel, biased at edges, but
    // over the frames' rotation every pixel samples every share: the image's total light over 64
    // frames must match the exact total within 3%, every pixel finite, background 0.
    SceneBuilder b = many_emitters(33, 11u);
    const Floor floor = make_floor();
    Harness harness(b.s, floor);
    const Vec3 albedo = {glm::unpackHalf1x16(floor.albedo[0][0]), glm::unpackHalf1x16(floor.albedo[0][1]),
                         glm::unpackHalf1x16(floor.albedo[0][2])};
    double exact = 0.0, mean = 0.0;
    for (uint32_t i = 0; i < kSize * kSize; ++i) {
        if (floor.position[i][3] == 0.0f) continue;
        const Vec3 e = reference(b.s, {floor.position[i][0], 0.0, floor.position[i][2]}, albedo);
        exact += e[0] + e[1] + e[2];
    }
    constexpr int frames = 64;
    for (int f = 0; f < frames; ++f) {
        const auto image = harness.run(uint32_t(f), 8, false, 0.0f, 4, 2);
        REQUIRE(harness.counts.cut_short == 0);
        for (uint32_t i = 0; i < kSize * kSize; ++i) {
            for (int c = 0; c < 3; ++c) REQUIRE(std::isfinite(image[i][c]));
            if (floor.position[i][3] == 0.0f) {
                CHECK(image[i][0] == 0.0f);
                continue;
            }
            mean += double(image[i][0]) + image[i][1] + image[i][2];
        }
    }
    mean /= frames;
    CHECK(exact > 0.0);
    CHECK(mean == doctest::Approx(exact).epsilon(0.03));
}

TEST_CASE("direct light tree: the same seed gives the same image, another seed another one") {
    SceneBuilder b = many_emitters(20, 5u);
    const Floor floor = make_floor();
    Harness harness(b.s, floor);
    const auto a = harness.run(1, 4, true);
    CHECK(harness.run(1, 4, true) == a);
    CHECK(harness.run(2, 4, true) != a);
}

TEST_CASE("direct light tree: bad options and scenes without tree lights are refused by name") {
    vplkit::stages::RtslcOptions options;
    options.interleave = 3;  // does not divide the block size 8
    options.samples_per_pixel = 9;
    CHECK_THROWS_WITH_AS(vplkit::stages::validate_direct_light_tree(options), doctest::Contains("interleav"),
                         vplkit::Error);
    options.interleave = 1;
    options.samples_per_pixel = 65;
    CHECK_THROWS_WITH_AS(vplkit::stages::validate_direct_light_tree(options), doctest::Contains("direct light tree"),
                         vplkit::Error);
    // Only a directional light: nothing to build a tree over.
    SceneBuilder b;
    vplkit::scene::Light sun;
    sun.type = vplkit::scene::LightType::directional;
    b.s.lights = {sun};
    vplkit::Context& ctx = vplkit::test::context();
    const auto emitters = vplkit::upload_emitters(ctx, b.s);
    CHECK_THROWS_WITH_AS(vplkit::GpuLightTree::create(ctx, b.s, emitters), doctest::Contains("no"), vplkit::Error);
}

TEST_CASE("triangle emission: an emissive texture counts with its mean over the triangle") {
    // A 2 x 1 texture: texel 0 white, texel 1 sRGB (128, 0, 64). Triangles whose UVs lie in one
    // texel emit factor x that texel (linear); one over both, factor x the area-weighted mean.
    SceneBuilder b;
    const uint32_t m = b.add_emissive({2.0f, 3.0f, 4.0f}, false);
    b.s.materials[m].emissive_texture = 0;
    b.s.textures.push_back({0, {}});
    vplkit::scene::Image image;
    image.width = 2;
    image.height = 1;
    image.rgba = {255, 255, 255, 255, 128, 0, 64, 255};
    image.srgb = true;
    b.s.images.push_back(image);
    auto add = [&](glm::vec2 a, glm::vec2 c, glm::vec2 d) {
        add_small_emitter(b, {0.0f, 1.0f, 0.0f}, 0.2f, true, m);
        const size_t base = b.s.vertices.size() - 3;
        b.s.vertices[base].uv0 = a;
        b.s.vertices[base + 1].uv0 = c;
        b.s.vertices[base + 2].uv0 = d;
        return b.s.emissive_triangles.back();
    };
    const uint32_t white = add({0.05f, 0.1f}, {0.45f, 0.2f}, {0.2f, 0.9f});
    const uint32_t coloured = add({1.55f, 0.1f}, {1.95f, 0.2f}, {1.7f, 0.9f});  // wraps to [0.55, 0.95] (repeat)
    const uint32_t both = add({0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f});        // 3/4 of it has u < 1/2
    auto linear = [](double c) { return std::pow((c / 255.0 + 0.055) / 1.055, 2.4); };
    const glm::vec3 w = vplkit::triangle_emission(b.s, white);
    const glm::vec3 k = vplkit::triangle_emission(b.s, coloured);
    const glm::vec3 h = vplkit::triangle_emission(b.s, both);
    CHECK(w.x == doctest::Approx(2.0));
    CHECK(w.z == doctest::Approx(4.0));
    CHECK(k.x == doctest::Approx(2.0 * linear(128)));
    CHECK(k.y == 0.0f);
    CHECK(k.z == doctest::Approx(4.0 * linear(64)));
    CHECK(h.y == doctest::Approx(3.0 * 0.75).epsilon(0.05));
    // The tree's power and the flat sampler's triangles use it.
    const auto triangles = vplkit::emitter_triangles(b.s);
    REQUIRE(triangles.size() == 3);
    CHECK(triangles[1].triangle.radiance.x == doctest::Approx(k.x));
}
