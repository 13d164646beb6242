// GI at half resolution: gbuffer_downsample.comp and upsample_bilateral.comp on small synthetic
// G-buffers, against the double-precision reference (tests/reference/upsample_reference.cpp).
//
// The scene (full pixel (X, Y), spacing h = 0.1 world units, d_max = 0.5, n_min = 0.9):
//   plane A   X < 8,  Y < 8:   the floor y = 0, normal ~ +y (jittered by up to ~4 degrees)
//   plane B   X >= 8, Y < 8:   rises from a crease at x = 7.5 h at 60 degrees; <n_A, n_B> ~ 0.5
//   floor C   X <= 10, Y >= 8: parallel to A but 3 units below it (a depth jump, same normal)
//   background elsewhere, and holes at (2, 2) (a half-resolution sample) and (12, 3) (not one)
//   thin      X = 5, Y 2..5:   a one-pixel strip on odd columns, so no half sample lies on it;
//                              normal 53 degrees from A's: every tap dissimilar, all facing
//   isolated  (13, 9):         covered, among background samples only
//   facing    (9, 9):          covered, facing down, among C's upward samples
// Every pair of pixels the filter compares on one plane is < 0.15 apart with normals within
// ~8 degrees; across planes the dot products are <= 0.6 or the distances >= 2.9: no decision
// lies near a threshold (the reference's near_decision flags are asserted to be unset).
//
// Tolerance against the reference: relative 1e-6. The bilinear weights (0, 1/4, 1/2, 1) are
// exact in float; the GPU's sum of at most four positive terms and its division round each by
// 2^-24 relative, so a few 1e-7 in all, and the inputs are the same floats on both sides.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/stages/upsample.hpp"
#include "vplkit/upsample_counters.hpp"
#include "vplkit_test/context.hpp"
#include "upsample_reference.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

namespace {

namespace ref = vplkit::reference;
namespace stages = vplkit::stages;
using Texel = std::array<float, 4>;
using HalfTexel = std::array<uint16_t, 4>;

constexpr float kSpacing = 0.1f;
constexpr float kMinCos = 0.9f;
constexpr float kMaxDistance = 0.5f;

enum class Region { background, plane_a, plane_b, floor_c, thin, isolated, facing_away };

struct Scene {
    uint32_t width = 0, height = 0;
    std::vector<Region> regions;
    std::vector<Texel> position, normal, geometric;
    std::vector<HalfTexel> albedo, emission;
    Region region(uint32_t x, uint32_t y) const { return regions[size_t(y) * width + x]; }
};

HalfTexel to_half(float r, float g, float b, float a) {
    return {glm::packHalf1x16(r), glm::packHalf1x16(g), glm::packHalf1x16(b), glm::packHalf1x16(a)};
}

Region region_of(uint32_t x, uint32_t y) {
    if ((x == 2 && y == 2) || (x == 12 && y == 3)) return Region::background;
    if (x == 5 && y >= 2 && y <= 5) return Region::thin;
    if (x == 13 && y == 9) return Region::isolated;
    if (x == 9 && y == 9) return Region::facing_away;
    if (y < 8) return x < 8 ? Region::plane_a : Region::plane_b;
    return x <= 10 ? Region::floor_c : Region::background;
}

Scene make_scene(uint32_t width, uint32_t height) {
    Scene scene;
    scene.width = width;
    scene.height = height;
    std::mt19937 rng(width * 131 + height);
    std::uniform_real_distribution<float> jitter(-0.05f, 0.05f);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float c60 = 0.5f, s60 = std::sqrt(3.0f) / 2.0f;
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const Region region = region_of(x, y);
            const float fx = float(x) * kSpacing, fz = float(y) * kSpacing;
            glm::vec3 p{0.0f}, n{0.0f, 1.0f, 0.0f};
            switch (region) {
                case Region::background:
                    break;
                case Region::plane_a:
                    p = {fx, 0.0f, fz};
                    break;
                case Region::plane_b: {
                    const float along = (float(x) - 7.5f) * kSpacing;
                    p = {7.5f * kSpacing + along * c60, along * s60, fz};
                    n = {-s60, c60, 0.0f};
                    break;
                }
                case Region::floor_c:
                    p = {fx, -3.0f, fz};
                    break;
                // Off the pixel centre in x and z so that no two fallback candidates are at the
                // same distance.
                case Region::thin:
                    p = {fx + 0.013f, 0.05f, fz + 0.017f};
                    n = {0.0f, 0.6f, 0.8f};
                    break;
                case Region::isolated:
                    p = {fx, 0.3f, fz};
                    break;
                case Region::facing_away:
                    p = {fx, -2.98f, fz};
                    n = {0.0f, -1.0f, 0.0f};
                    break;
            }
            const bool planar = region == Region::plane_a || region == Region::plane_b || region == Region::floor_c;
            if (planar) n = glm::normalize(n + glm::vec3(jitter(rng), jitter(rng), jitter(rng)));
            const bool covered = region != Region::background;
            scene.regions.push_back(region);
            scene.position.push_back({p.x, p.y, p.z, covered ? 1.0f : 0.0f});
            scene.normal.push_back({n.x, n.y, n.z, unit(rng)});     // w: roughness
            scene.geometric.push_back({n.x, n.y, n.z, unit(rng)});  // w: metallic
            scene.albedo.push_back(to_half(unit(rng), unit(rng), unit(rng), 1.0f));
            scene.emission.push_back(to_half(unit(rng), 0.0f, unit(rng), 0.0f));
        }
    }
    return scene;
}

ref::Grid<ref::UpsampleTexel> reference_gbuffer(const Scene& scene) {
    ref::Grid<ref::UpsampleTexel> grid{scene.width, scene.height, {}};
    for (size_t i = 0; i < scene.position.size(); ++i) {
        const Texel& p = scene.position[i];
        const Texel& n = scene.normal[i];
        grid.texels.push_back({p[3] > 0.5f, {p[0], p[1], p[2]}, {n[0], n[1], n[2]}});
    }
    return grid;
}

vplkit::Image make_indirect(uint32_t width, uint32_t height, const std::string& name,
                            VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT) {
    return vplkit::Image::create(vplkit::test::context(), width, height, format, VK_IMAGE_USAGE_STORAGE_BIT, name);
}

vplkit::GbufferImages upload_gbuffer(const Scene& scene) {
    auto gbuffer = vplkit::GbufferImages::create(vplkit::test::context(), scene.width, scene.height);
    gbuffer.position.upload(scene.position);
    gbuffer.normal.upload(scene.normal);
    gbuffer.geometric_normal.upload(scene.geometric);
    gbuffer.albedo.upload(scene.albedo);
    gbuffer.emission.upload(scene.emission);
    return gbuffer;
}

struct GpuRun {
    std::vector<Texel> indirect;
    stages::UpsampleCounts counts;
};

// The downsample and the upsample in one pass list, as a renderer would record them (the GI
// stage between them replaced by uploading `half_radiance`); the list runs `runs` times.
GpuRun run_gpu(const Scene& scene, const std::vector<Texel>& half_radiance, int runs = 1) {
    vplkit::Context& ctx = vplkit::test::context();
    auto full = upload_gbuffer(scene);
    const uint32_t half_w = stages::half_resolution(scene.width), half_h = stages::half_resolution(scene.height);
    auto half = vplkit::GbufferImages::create(ctx, half_w, half_h);
    auto half_indirect = make_indirect(half_w, half_h, "half indirect");
    half_indirect.upload(half_radiance);
    auto full_indirect = make_indirect(scene.width, scene.height, "full indirect");
    auto counters = vplkit::create_upsample_counters(ctx);
    stages::UpsampleOptions options;
    options.min_cos = kMinCos;
    options.max_distance = kMaxDistance;
    vplkit::PassList passes("upsample test");
    stages::add_gbuffer_downsample_pass(ctx, passes, full, half);
    stages::add_upsample_passes(ctx, passes, full, half, half_indirect, full_indirect, counters, options);
    REQUIRE(passes.size() == 3);
    for (int i = 0; i < runs; ++i) passes.run(ctx);
    CHECK(passes.timings()[0].name == "gbuffer downsample");
    CHECK(passes.timings()[1].name == "upsample clear");
    CHECK(passes.timings()[2].name == "upsample");
    return {full_indirect.download<Texel>(), vplkit::read_upsample_counters(counters)};
}

// rgb in [0.1, 10] per half sample (alpha random too: the upsampler must drop it).
std::vector<Texel> random_radiance(uint32_t width, uint32_t height, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> value(0.1f, 10.0f);
    std::vector<Texel> out;
    for (uint32_t i = 0; i < width * height; ++i) out.push_back({value(rng), value(rng), value(rng), value(rng)});
    return out;
}

ref::Grid<ref::UpsampleVec3> reference_radiance(const std::vector<Texel>& texels, uint32_t width, uint32_t height) {
    ref::Grid<ref::UpsampleVec3> grid{width, height, {}};
    for (const Texel& t : texels) grid.texels.push_back({t[0], t[1], t[2]});
    return grid;
}

ref::UpsampleResult run_reference(const Scene& scene, const std::vector<Texel>& half_radiance) {
    const auto full = reference_gbuffer(scene);
    const auto half = ref::downsample_grid(full);
    return ref::upsample_reference(full, half, reference_radiance(half_radiance, half.width, half.height), kMinCos,
                                   kMaxDistance);
}

// Per plane: a value a blend across planes could not produce by accident.
Texel plane_constant(Region region) {
    switch (region) {
        case Region::plane_a:
            return {1.0f, 2.0f, 3.0f, 0.0f};
        case Region::plane_b:
            return {100.0f, 200.0f, 300.0f, 0.0f};
        case Region::floor_c:
            return {1e4f, 2e4f, 3e4f, 0.0f};
        default:
            return {0.0f, 0.0f, 0.0f, 0.0f};
    }
}

}  // namespace

TEST_CASE("upsample: half_resolution rounds up") {
    CHECK(stages::half_resolution(1) == 1);
    CHECK(stages::half_resolution(2) == 1);
    CHECK(stages::half_resolution(15) == 8);
    CHECK(stages::half_resolution(16) == 8);
    CHECK(stages::half_resolution(1281) == 641);
    CHECK(stages::half_resolution(UINT32_MAX) == 2147483648u);
}

TEST_CASE("upsample: the downsample copies exactly the even pixels of every image, odd sizes too") {
    vplkit::Context& ctx = vplkit::test::context();
    for (const auto& [width, height] : {std::array<uint32_t, 2>{16, 12}, {15, 11}, {1, 1}, {3, 2}, {17, 1}}) {
        CAPTURE(width);
        CAPTURE(height);
        // Random bits of every channel, so a copy of the wrong pixel or channel shows; halves
        // kept normal and finite (a float round trip keeps those exactly).
        std::mt19937 rng(width * 7 + height);
        std::uniform_real_distribution<float> value(-4.0f, 4.0f);
        auto random_texel = [&] { return Texel{value(rng), value(rng), value(rng), value(rng)}; };
        auto random_half = [&] {
            auto v = [&] { return std::copysign(0.01f + std::abs(value(rng)), value(rng)); };
            return to_half(v(), v(), v(), v());
        };
        Scene scene;
        scene.width = width;
        scene.height = height;
        for (uint32_t i = 0; i < width * height; ++i) {
            scene.position.push_back(random_texel());
            scene.normal.push_back(random_texel());
            scene.geometric.push_back(random_texel());
            scene.albedo.push_back(random_half());
            scene.emission.push_back(random_half());
        }
        auto full = upload_gbuffer(scene);
        auto half = vplkit::GbufferImages::create(ctx, stages::half_resolution(width), stages::half_resolution(height));
        vplkit::PassList passes("downsample test");
        stages::add_gbuffer_downsample_pass(ctx, passes, full, half);
        passes.run(ctx);
        auto expect = [&](const auto& texels, auto downloaded) {
            using T = typename std::decay_t<decltype(texels)>::value_type;
            const auto expected = ref::downsample_grid(ref::Grid<T>{width, height, texels});
            REQUIRE(downloaded.size() == expected.texels.size());
            for (size_t i = 0; i < downloaded.size(); ++i) {
                CAPTURE(i);
                CHECK(downloaded[i] == expected.texels[i]);
            }
        };
        expect(scene.position, half.position.download<Texel>());
        expect(scene.normal, half.normal.download<Texel>());
        expect(scene.geometric, half.geometric_normal.download<Texel>());
        expect(scene.albedo, half.albedo.download<HalfTexel>());
        expect(scene.emission, half.emission.download<HalfTexel>());
    }
}

TEST_CASE("upsample: matches the double reference on a crease, a depth jump and background") {
    for (const auto& [width, height] : {std::array<uint32_t, 2>{16, 12}, {15, 11}}) {
        CAPTURE(width);
        CAPTURE(height);
        const Scene scene = make_scene(width, height);
        const uint32_t half_w = stages::half_resolution(width), half_h = stages::half_resolution(height);
        const auto radiance = random_radiance(half_w, half_h, width + height);
        const auto gpu = run_gpu(scene, radiance);
        const auto expected = run_reference(scene, radiance);
        int blended = 0;
        for (uint32_t y = 0; y < height; ++y) {
            for (uint32_t x = 0; x < width; ++x) {
                CAPTURE(x);
                CAPTURE(y);
                const size_t i = size_t(y) * width + x;
                const Texel& t = gpu.indirect[i];
                const ref::UpsampledPixel& e = expected.pixels[i];
                REQUIRE_FALSE(e.near_decision);  // the scene keeps every decision clear (top of file)
                CHECK(t[3] == 0.0f);
                for (int c = 0; c < 3; ++c) {
                    CHECK(std::isfinite(t[c]));
                    CHECK(double(t[c]) == doctest::Approx(e.radiance[c]).epsilon(1e-6));
                }
                blended += e.outcome == ref::UpsampleOutcome::blended;
                // Even pixels are their own half sample (distance 0, the same normal): a copy,
                // bit for bit, whatever the neighbours.
                if (x % 2 == 0 && y % 2 == 0 && scene.position[i][3] > 0.5f) {
                    const Texel& s = radiance[size_t(y / 2) * half_w + x / 2];
                    CHECK(t == Texel{s[0], s[1], s[2], 0.0f});
                }
                // What the scene was built to show, pixel by pixel.
                switch (scene.region(x, y)) {
                    case Region::background:
                        CHECK(e.outcome == ref::UpsampleOutcome::background);
                        break;
                    case Region::thin:
                        CHECK(e.outcome == ref::UpsampleOutcome::fallback);
                        break;
                    case Region::isolated:
                    case Region::facing_away:
                        CHECK(e.outcome == ref::UpsampleOutcome::empty);
                        break;
                    default:
                        CHECK(e.outcome == ref::UpsampleOutcome::blended);
                        break;
                }
            }
        }
        CHECK(expected.fallback_pixels == 4);  // the thin strip
        CHECK(expected.empty_pixels == 2);     // the isolated and the facing-away pixel
        CHECK(gpu.counts.fallback_pixels == expected.fallback_pixels);
        CHECK(gpu.counts.empty_pixels == expected.empty_pixels);
        CHECK(blended > int(width * height) / 2);
    }
}

TEST_CASE("upsample: a constant field stays constant") {
    const Scene scene = make_scene(16, 12);
    const Texel value{0.7f, 1.3f, 2.9f, 5.0f};
    const auto gpu = run_gpu(scene, std::vector<Texel>(8 * 6, value));
    for (size_t i = 0; i < gpu.indirect.size(); ++i) {
        CAPTURE(i);
        const Region region = scene.regions[i];
        const Texel& t = gpu.indirect[i];
        if (region == Region::background || region == Region::isolated || region == Region::facing_away) {
            CHECK(t == Texel{0, 0, 0, 0});  // no surface, or nothing to take light from
            continue;
        }
        // Normalized weights: a blend of equal values is that value (to the float rounding of
        // (sum w_k v) / (sum w_k)); the fallback pixels copy one.
        for (int c = 0; c < 3; ++c) CHECK(t[c] == doctest::Approx(value[c]).epsilon(1e-6));
        CHECK(t[3] == 0.0f);
    }
}

TEST_CASE("upsample: nothing bleeds across the crease or the depth jump") {
    const Scene scene = make_scene(16, 12);
    std::vector<Texel> radiance;
    for (uint32_t j = 0; j < 6; ++j) {
        for (uint32_t i = 0; i < 8; ++i) radiance.push_back(plane_constant(scene.region(2 * i, 2 * j)));
    }
    const auto gpu = run_gpu(scene, radiance);
    int next_to_crease = 0, next_to_jump = 0;
    for (uint32_t y = 0; y < 12; ++y) {
        for (uint32_t x = 0; x < 16; ++x) {
            const Region region = scene.region(x, y);
            if (region != Region::plane_a && region != Region::plane_b && region != Region::floor_c) continue;
            CAPTURE(x);
            CAPTURE(y);
            // Each plane's pixels carry only their own plane's light, also those whose
            // bilinear footprint reaches over the crease (x = 7) or the jump (y = 7).
            const Texel expected = plane_constant(region);
            const Texel& t = gpu.indirect[size_t(y) * 16 + x];
            for (int c = 0; c < 3; ++c) CHECK(t[c] == doctest::Approx(expected[c]).epsilon(1e-6));
            next_to_crease += x == 7 && y < 8;
            next_to_jump += y == 7 && x < 8;
        }
    }
    CHECK(next_to_crease == 8);
    CHECK(next_to_jump == 8);
}

TEST_CASE("upsample: fallback and empty pixels are counted, and the counters cleared on every run") {
    const Scene scene = make_scene(16, 12);
    std::vector<Texel> radiance;
    for (uint32_t j = 0; j < 6; ++j) {
        for (uint32_t i = 0; i < 8; ++i) radiance.push_back(plane_constant(scene.region(2 * i, 2 * j)));
    }
    // Run twice: "upsample clear" zeroes the counters, so they are not 8 and 4.
    const auto gpu = run_gpu(scene, radiance, 2);
    CHECK(gpu.counts.fallback_pixels == 4);
    CHECK(gpu.counts.empty_pixels == 2);
    // The thin strip takes its nearest facing sample: plane A's, the only plane around it.
    for (uint32_t y = 2; y <= 5; ++y) {
        const Texel& t = gpu.indirect[size_t(y) * 16 + 5];
        CHECK(t == plane_constant(Region::plane_a));
    }
    CHECK(gpu.indirect[9 * 16 + 13] == Texel{0, 0, 0, 0});
    CHECK(gpu.indirect[9 * 16 + 9] == Texel{0, 0, 0, 0});
}

TEST_CASE("upsample: bad options and mismatched sizes are refused") {
    vplkit::Context& ctx = vplkit::test::context();
    const Scene scene = make_scene(16, 12);
    auto full = upload_gbuffer(scene);
    auto half = vplkit::GbufferImages::create(ctx, 8, 6);
    auto wrong_half = vplkit::GbufferImages::create(ctx, 8, 7);
    auto half_indirect = make_indirect(8, 6, "half indirect");
    auto full_indirect = make_indirect(16, 12, "full indirect");
    auto counters = vplkit::create_upsample_counters(ctx);
    vplkit::PassList passes;
    stages::UpsampleOptions good;
    good.max_distance = kMaxDistance;

    CHECK_THROWS_WITH_AS(stages::add_gbuffer_downsample_pass(ctx, passes, full, wrong_half),
                         doctest::Contains("half G-buffer is 8x7, but half of the 16x12 G-buffer is 8x6"),
                         vplkit::Error);

    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (float min_cos : {nan, 1.0f, -1.5f, 2.0f}) {
        CAPTURE(min_cos);
        stages::UpsampleOptions o = good;
        o.min_cos = min_cos;
        CHECK_THROWS_WITH_AS(
            stages::add_upsample_passes(ctx, passes, full, half, half_indirect, full_indirect, counters, o),
            doctest::Contains("min_cos"), vplkit::Error);
    }
    // The default max_distance (0) must be replaced by a scene-relative one.
    for (float max_distance : {0.0f, -1.0f, nan, inf}) {
        CAPTURE(max_distance);
        stages::UpsampleOptions o = good;
        o.max_distance = max_distance;
        CHECK_THROWS_WITH_AS(
            stages::add_upsample_passes(ctx, passes, full, half, half_indirect, full_indirect, counters, o),
            doctest::Contains("max_distance"), vplkit::Error);
    }
    CHECK_THROWS_WITH_AS(
        stages::add_upsample_passes(ctx, passes, full, wrong_half, half_indirect, full_indirect, counters, good),
        doctest::Contains("half G-buffer is 8x7"), vplkit::Error);
    auto wrong_size = make_indirect(8, 5, "small half");
    CHECK_THROWS_WITH_AS(
        stages::add_upsample_passes(ctx, passes, full, half, wrong_size, full_indirect, counters, good),
        doctest::Contains("'small half' (8x5"), vplkit::Error);
    auto wrong_format = make_indirect(16, 12, "half-float full", VK_FORMAT_R16G16B16A16_SFLOAT);
    CHECK_THROWS_WITH_AS(
        stages::add_upsample_passes(ctx, passes, full, half, half_indirect, wrong_format, counters, good),
        doctest::Contains("'half-float full'"), vplkit::Error);
    auto tiny = vplkit::Buffer::create(ctx, 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "tiny");
    CHECK_THROWS_WITH_AS(stages::add_upsample_passes(ctx, passes, full, half, half_indirect, full_indirect, tiny, good),
                         doctest::Contains("'tiny' is too small"), vplkit::Error);
    CHECK(passes.size() == 0);  // nothing half-added

    CHECK(stages::upsample_options_for_scene(10.0f).max_distance == doctest::Approx(0.2f));
    CHECK(stages::upsample_options_for_scene(10.0f).min_cos == 0.9f);
    for (float scale : {0.0f, -1.0f, nan, inf}) {
        CAPTURE(scale);
        CHECK_THROWS_WITH_AS(stages::upsample_options_for_scene(scale), doctest::Contains("scene scale"),
                             vplkit::Error);
    }
}
