// The splatting raster pipeline (flc_splat_proxy.vert + flc_splat_shade.frag, the FLC paper sec. 5)
// against a CPU reference in double: on a 64 x 64 G-buffer of a floor seen by a perspective camera
// (each pixel's position is the floor point its centre sees, so the G-buffer agrees with the
// camera the proxies are projected with), every pixel must be the sum over the VPLs of
// f~^k(d(x)) x the VPL's unshadowed light (vpl_reference.cpp's vpl_contribution, the formula of
// vpl_eval.glsl).
//
// Tolerance per pixel: 3e-4 x the expected value (the glTF BRDF in float against double, as in
// the exact gi test) + 1e-5 x the sum of the VPLs' unweighted light there (f~^k is a hat of slope
// at most 1 / (D_k - D_{k-1}); the float support distance's rounding, ~1e-6 relative, moves a
// weight by less than 1e-5 here). The VPLs are of levels 0..2 of 4, so every support is bounded
// (the last level's reaches everything in front of its VPL: flc_partition.glsl).
// Supports: a pixel that every VPL's support misses by more than 1e-4 relative must be exactly 0,
// and background pixels too. Blending: two VPLs drawn together give exactly what each gives alone,
// summed in float (1e-6 relative for the order of the two float additions).
// Every run also checks the draw arguments flc_splat_args.comp writes (one rectangle per VPL).
// Interleaved sub-tiles (n = 2, and n = 3 on a size that is not a multiple of it), flc_untile.comp:
// untiled, pixel (x, y) must be n^2 x the reference sum over the VPLs i with i mod n^2 = (x mod n)
// + n (y mod n) (same tolerance); blurred, the mean of that over the n x n window's covered pixels (the floor is
// one plane: every covered neighbour is on p's surface), within the window's largest tolerance.

#include "synthetic_scene.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/flc.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit_test/context.hpp"
#include "flc_reference.hpp"
#include "vpl_reference.hpp"

#include <doctest/doctest.h>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

namespace ref = vplkit::reference;
using vplkit::test::Pixel;
using vplkit::test::TestVpl;
using Texel = std::array<float, 4>;

constexpr uint32_t kSize = 64;
constexpr float kSceneScale = 3.0f;

// 4 levels, D = 0.6, 0.85, 1.2, 1.7: levels 0..2 have supports of radius up to 0.85 on a floor 6
// wide (level 3, the last, would reach the whole half-space in front of its VPL).
vplkit::stages::FlcPartition partition() {
    return {4, 0.05f, 0.6f, 2.0f};
}

ref::FlcParameters reference_partition() {
    const auto p = partition();
    ref::FlcParameters r;
    r.level_count = int(p.level_count);
    r.s0 = p.s0;
    r.d0 = p.d0;
    r.mu = p.mu;
    return r;
}

struct SplatVpl {
    TestVpl vpl;
    int level = 0;
};

struct Floor {
    vplkit::stages::CameraView view;
    glm::vec3 camera{0.0f, 3.0f, 3.5f};
    std::vector<Pixel> pixels;
};

// The floor y = 0, [-3, 3]^2, seen from above; pixels whose centre misses it are background.
Floor make_floor() {
    Floor f;
    const glm::mat4 view = glm::lookAt(f.camera, glm::vec3(0.0f, 0.0f, -0.3f), glm::vec3(0.0f, 1.0f, 0.0f));
    f.view.view_projection = vplkit::stages::vulkan_perspective(1.1f, 1.0f, 0.1f, 50.0f) * view;
    f.view.position = f.camera;
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(f.view.view_projection));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            const double nx = (x + 0.5) / kSize * 2.0 - 1.0, ny = (y + 0.5) / kSize * 2.0 - 1.0;
            const glm::dvec4 a = inverse * glm::dvec4(nx, ny, 0.0, 1.0), b = inverse * glm::dvec4(nx, ny, 1.0, 1.0);
            const glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
            Pixel p;
            p.roughness = 0.3f + 0.7f * unit(rng);
            p.metallic = unit(rng) < 0.2f ? 1.0f : 0.0f;
            p.albedo = {vplkit::test::half_round(unit(rng)), vplkit::test::half_round(unit(rng)),
                        vplkit::test::half_round(unit(rng))};
            if (p1.y < p0.y) {
                const glm::dvec3 hit = p0 + (p1 - p0) * (p0.y / (p0.y - p1.y));
                p.covered = std::abs(hit.x) < 3.0 && std::abs(hit.z) < 3.0;
                p.position = glm::vec3(float(hit.x), 0.0f, float(hit.z));
            }
            f.pixels.push_back(p);
        }
    }
    return f;
}

std::vector<Texel> run_gpu(const Floor& floor, const std::vector<SplatVpl>& vpls,
                           const vplkit::stages::FlcSplatOptions& options = {}) {
    vplkit::Context& ctx = vplkit::test::context();
    std::vector<TestVpl> plain;
    for (const auto& v : vpls) plain.push_back(v.vpl);
    const std::vector<glm::vec3> no_triangles = {glm::vec3(-3, 0, -3), glm::vec3(3, 0, 3), glm::vec3(3, 0, -3)};
    auto scene = vplkit::test::upload(ctx, kSize, kSize, floor.pixels, no_triangles, plain);
    const auto count = uint32_t(vpls.size());
    std::vector<vplkit::shaders::FlcCandidate> candidates(count);
    std::vector<uint32_t> kept(count);
    std::vector<uint32_t> counts(2 + partition().level_count, 0);
    for (uint32_t i = 0; i < count; ++i) {
        candidates[i].level = vpls[i].level;
        kept[i] = i;
        ++counts[2 + vpls[i].level];
    }
    counts[0] = count;
    auto create = [&](VkDeviceSize bytes, VkBufferUsageFlags usage, const char* name) {
        return vplkit::Buffer::create(ctx, bytes, usage, vplkit::MemoryUse::device, name);
    };
    auto candidate_buffer = create(count * sizeof(candidates[0]), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "candidates");
    auto kept_buffer = create(count * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "kept");
    auto count_buffer =
        create(vplkit::stages::flc_count_bytes(partition().level_count), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "counts");
    auto args = create(vplkit::stages::kFlcDrawArgsBytes,
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, "draw args");
    candidate_buffer.upload(candidates);
    kept_buffer.upload(kept);
    count_buffer.upload(counts);
    auto indirect = vplkit::Image::create(ctx, kSize, kSize, vplkit::stages::kFlcIndirectFormat,
                                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT, "indirect");
    const uint32_t tiled_side = options.subtiles * vplkit::stages::flc_subtile_side(kSize, options.subtiles);
    auto tiled = vplkit::Image::create(ctx, tiled_side, tiled_side, vplkit::stages::kFlcIndirectFormat,
                                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT, "tiled");
    vplkit::PassList passes("flc splat test");
    vplkit::stages::add_flc_splat_passes(ctx, passes, {candidate_buffer, count_buffer, kept_buffer, scene.vpls, args},
                                         scene.gbuffer, indirect, floor.view, partition(), count, kSceneScale, options,
                                         tiled);
    passes.run(ctx);
    // flc_splat_args.comp: the indirect draw is one 6-vertex rectangle per kept VPL (the kept
    // count, at most the VPL buffer's capacity, here both `count`), from vertex and instance 0.
    CHECK(args.download<uint32_t>(4) == std::vector<uint32_t>{6u, count, 0u, 0u});
    return indirect.download<Texel>();
}

struct Expected {
    std::vector<std::array<double, 3>> radiance;
    std::vector<double> bound;  // the tolerance (top of the file)
    std::vector<bool> outside;  // beyond every support by more than 1e-4 relative
};

// subtiles n > 1: pixel (x, y) sums only its sub-tile's VPLs, x n^2 (untiled, no blur).
Expected run_reference(const Floor& floor, const std::vector<SplatVpl>& vpls, uint32_t subtiles = 1) {
    const ref::FlcParameters p = reference_partition();
    const double min_distance = ref::kVplMinDistanceFraction * kSceneScale;
    Expected e;
    for (size_t pixel = 0; pixel < floor.pixels.size(); ++pixel) {
        const Pixel& px = floor.pixels[pixel];
        const size_t tile = (pixel % kSize) % subtiles + subtiles * ((pixel / kSize) % subtiles);
        const double share = double(subtiles * subtiles);
        std::array<double, 3> sum{0, 0, 0};
        double unweighted = 0.0;
        bool outside = true;
        if (px.covered) {
            const ref::ShadingPoint x = vplkit::test::shading_point(px);
            const glm::dvec3 to_eye = glm::normalize(glm::dvec3(floor.camera) - glm::dvec3(px.position));
            const ref::Vec3 wo = {to_eye.x, to_eye.y, to_eye.z};
            for (size_t i = 0; i < vpls.size(); ++i) {
                if (i % (subtiles * subtiles) != tile) continue;
                const SplatVpl& v = vpls[i];
                const ref::VplDesc desc = vplkit::test::reference_vpls(std::vector<TestVpl>{v.vpl})[0];
                const double d = ref::flc_support_distance(x.position, desc.position, desc.normal);
                const double reach = v.level == p.level_count - 1 ? std::numeric_limits<double>::infinity()
                                                                  : ref::flc_influence_distance(p, v.level + 1);
                if (d <= reach * (1.0 + 1e-4)) outside = false;
                const ref::Vec3 c = ref::vpl_contribution(x, wo, desc, min_distance);
                const double w = ref::flc_partition_weight(p, v.level, d);
                for (int k = 0; k < 3; ++k) sum[k] += share * w * c[k];
                unweighted += share * std::max({c[0], c[1], c[2]});
            }
        }
        e.radiance.push_back(sum);
        e.bound.push_back(3e-4 * std::max({sum[0], sum[1], sum[2]}) + 1e-5 * unweighted);
        e.outside.push_back(outside);
    }
    return e;
}

// VPLs near the floor: on a wall facing +x, hanging above it facing down (tilted), low ones
// facing sideways (grazing); every level.
std::vector<SplatVpl> scattered_vpls() {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<SplatVpl> vpls;
    for (int i = 0; i < 24; ++i) {
        SplatVpl v;
        v.level = i % 3;
        const glm::vec3 flux(0.5f + unit(rng), 0.5f + unit(rng), 0.5f + unit(rng));
        if (i < 8) {
            v.vpl = {{-2.0f, 0.05f + 0.6f * unit(rng), -2.0f + 4.0f * unit(rng)}, {1.0f, 0.0f, 0.0f}, flux};
        } else if (i < 18) {
            const glm::vec3 n = glm::normalize(glm::vec3(unit(rng) - 0.5f, -1.0f, unit(rng) - 0.5f));
            v.vpl = {{-2.5f + 5.0f * unit(rng), 0.1f + 0.9f * unit(rng), -2.5f + 5.0f * unit(rng)}, n, flux};
        } else {
            const float a = 6.2832f * unit(rng);
            v.vpl = {{-2.0f + 4.0f * unit(rng), 0.02f, -2.0f + 4.0f * unit(rng)},
                     glm::normalize(glm::vec3(std::cos(a), -0.05f, std::sin(a))),
                     flux};
        }
        vpls.push_back(v);
    }
    return vpls;
}

}  // namespace

TEST_CASE("flc splat: 24 VPLs of 3 levels match the double reference, and nothing lands outside the supports") {
    const Floor floor = make_floor();
    const auto vpls = scattered_vpls();
    const auto gpu = run_gpu(floor, vpls);
    const Expected expected = run_reference(floor, vpls);
    int compared = 0, lit = 0, outside = 0, background = 0;
    for (size_t i = 0; i < gpu.size(); ++i) {
        CAPTURE(i);
        const Texel& t = gpu[i];
        if (!floor.pixels[i].covered) {
            CHECK(t == Texel{0, 0, 0, 0});
            ++background;
            continue;
        }
        if (expected.outside[i]) {
            CHECK(t == Texel{0, 0, 0, 0});  // beyond every support: exactly nothing
            ++outside;
            continue;
        }
        ++compared;
        lit += t[0] > 0.0f;
        for (int k = 0; k < 3; ++k) CHECK(std::abs(double(t[k]) - expected.radiance[i][k]) <= expected.bound[i]);
        CHECK(t[3] == 0.0f);
    }
    MESSAGE("compared " << compared << ", lit " << lit << ", outside every support " << outside << ", background "
                        << background);
    CHECK(lit > 300);         // the VPLs light a good part of the floor...
    CHECK(outside > 300);     // ...and leave a good part dark
    CHECK(background > 100);  // the camera sees past the floor's far edge
}

TEST_CASE("flc splat: blending adds, two VPLs give the sum of each alone") {
    const Floor floor = make_floor();
    const SplatVpl a{{{-0.1f, 0.3f, 0.0f}, glm::normalize(glm::vec3(0.2f, -1.0f, 0.0f)), {1.0f, 0.5f, 0.25f}}, 0};
    const SplatVpl b{{{0.1f, 0.3f, 0.05f}, glm::normalize(glm::vec3(-0.3f, -1.0f, 0.1f)), {0.3f, 0.9f, 0.6f}}, 0};
    const auto alone_a = run_gpu(floor, {a});
    const auto alone_b = run_gpu(floor, {b});
    const auto both = run_gpu(floor, {a, b});
    int overlap = 0;
    for (size_t i = 0; i < both.size(); ++i) {
        CAPTURE(i);
        overlap += alone_a[i][0] > 0.0f && alone_b[i][0] > 0.0f;
        for (int k = 0; k < 4; ++k) {
            const float sum = alone_a[i][k] + alone_b[i][k];
            CHECK(std::abs(both[i][k] - sum) <= 1e-6f * sum);
        }
    }
    CHECK(overlap > 20);  // the supports overlap (37 pixels): an overwrite would show
}

TEST_CASE("flc splat: interleaved sub-tiles, untiled and blurred by flc_untile, match the reference's sub-tile sums") {
    const Floor floor = make_floor();
    const auto vpls = scattered_vpls();
    for (uint32_t n : {2u, 3u}) {
        CAPTURE(n);
        const Expected expected = run_reference(floor, vpls, n);
        vplkit::stages::FlcSplatOptions options;
        options.subtiles = n;
        options.blur = false;
        const auto untiled = run_gpu(floor, vpls, options);
        int compared = 0;
        for (size_t i = 0; i < untiled.size(); ++i) {
            CAPTURE(i);
            if (!floor.pixels[i].covered || expected.outside[i]) {
                CHECK(untiled[i] == Texel{0, 0, 0, 0});
                continue;
            }
            ++compared;
            for (int k = 0; k < 3; ++k) {
                CHECK(std::abs(double(untiled[i][k]) - expected.radiance[i][k]) <= expected.bound[i]);
            }
        }
        options.blur = true;
        const auto blurred = run_gpu(floor, vpls, options);
        const int first = -int(n / 2);
        int blurred_compared = 0;
        for (int y = 0; y < int(kSize); ++y) {
            for (int x = 0; x < int(kSize); ++x) {
                const size_t i = size_t(y) * kSize + x;
                CAPTURE(i);
                if (!floor.pixels[i].covered) {
                    CHECK(blurred[i] == Texel{0, 0, 0, 0});
                    continue;
                }
                std::array<double, 3> sum{0, 0, 0};
                double bound = 0.0, count = 0.0;
                for (int dy = first; dy < first + int(n); ++dy) {
                    for (int dx = first; dx < first + int(n); ++dx) {
                        const int qx = x + dx, qy = y + dy;
                        if (qx < 0 || qy < 0 || qx >= int(kSize) || qy >= int(kSize)) continue;
                        const size_t q = size_t(qy) * kSize + qx;
                        if (!floor.pixels[q].covered) continue;
                        for (int k = 0; k < 3; ++k) sum[k] += expected.radiance[q][k];
                        bound = std::max(bound, expected.bound[q]);
                        count += 1.0;
                    }
                }
                ++blurred_compared;
                for (int k = 0; k < 3; ++k) CHECK(std::abs(double(blurred[i][k]) - sum[k] / count) <= bound);
            }
        }
        MESSAGE(n << "x" << n << " sub-tiles: untiled " << compared << " pixels compared, blurred "
                  << blurred_compared);
        CHECK(blurred_compared > 2000);
    }
}

TEST_CASE("flc splat: bad arguments are refused with a clear error") {
    vplkit::Context& ctx = vplkit::test::context();
    auto buffer = vplkit::Buffer::create(ctx, 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "b");
    auto gbuffer = vplkit::GbufferImages::create(ctx, 8, 8);
    auto small = vplkit::Image::create(ctx, 4, 4, vplkit::stages::kFlcIndirectFormat,
                                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "small");
    auto right = vplkit::Image::create(ctx, 8, 8, vplkit::stages::kFlcIndirectFormat,
                                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "right");
    vplkit::PassList passes("flc splat errors");
    const vplkit::stages::FlcSplatBuffers buffers{buffer, buffer, buffer, buffer, buffer};
    const vplkit::stages::CameraView view;
    CHECK_THROWS_WITH_AS(
        vplkit::stages::add_flc_splat_passes(ctx, passes, buffers, gbuffer, small, view, partition(), 1, 1.0f),
        doctest::Contains("indirect image is 4x4"), vplkit::Error);
    CHECK_THROWS_WITH_AS(
        vplkit::stages::add_flc_splat_passes(ctx, passes, buffers, gbuffer, right, view, partition(), 0, 1.0f),
        doctest::Contains("no VPL"), vplkit::Error);
    CHECK_THROWS_WITH_AS(
        vplkit::stages::add_flc_splat_passes(ctx, passes, buffers, gbuffer, right, view, partition(), 100, 1.0f),
        doctest::Contains("'kept triangles' has 256 bytes"), vplkit::Error);
    CHECK_THROWS_WITH_AS(
        vplkit::stages::add_flc_splat_passes(ctx, passes, buffers, gbuffer, right, view, partition(), 1, std::nanf("")),
        doctest::Contains("scene scale"), vplkit::Error);
}
