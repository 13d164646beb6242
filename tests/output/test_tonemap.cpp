// tonemap.comp against the double-precision reference.
// Tolerance: exact 8-bit values, except where the reference's encoded value lies within 2e-3 of
// a rounding border (k + 0.5) / 255: float pow/division in the shader and the driver's UNORM
// rounding may land on either side there; such channels may differ by one step.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/tonemap.hpp"
#include "vplkit_test/context.hpp"
#include "tonemap_reference.hpp"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

namespace {

struct Result {
    std::vector<std::array<uint8_t, 4>> texels;
    uint32_t non_finite = 0;
};

Result run_tonemap(uint32_t width, uint32_t height, const std::vector<std::array<float, 4>>& hdr_texels,
                   float exposure) {
    vplkit::Context& ctx = vplkit::test::context();
    auto hdr =
        vplkit::Image::create(ctx, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "hdr");
    auto ldr = vplkit::Image::create(ctx, width, height, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT, "ldr");
    auto stats = vplkit::Buffer::create(ctx, vplkit::stages::kTonemapStatsBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vplkit::MemoryUse::device, "tonemap stats");
    hdr.upload(hdr_texels);
    vplkit::PassList passes("tonemap test");
    vplkit::stages::add_tonemap_passes(ctx, passes, hdr, ldr, stats, exposure);
    passes.run(ctx);
    Result r;
    r.texels = ldr.download<std::array<uint8_t, 4>>();
    r.non_finite = stats.download<uint32_t>(1)[0];
    return r;
}

}  // namespace

TEST_CASE("tonemap: matches the reference from 1e-6 to 1e6") {
    const uint32_t width = 37, height = 19;  // not a multiple of the 16 x 16 workgroup
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> log10_value(-6.0f, 6.0f);
    std::vector<std::array<float, 4>> hdr(width * height);
    for (auto& t : hdr) {
        t = {std::pow(10.0f, log10_value(rng)), std::pow(10.0f, log10_value(rng)), std::pow(10.0f, log10_value(rng)),
             1.0f};
    }
    hdr[0] = {0.0f, 0.0f, 0.0f, 1.0f};
    hdr[1] = {-5.0f, 0.5f, 1e30f, 1.0f};  // negative radiance clamps to 0; huge saturates
    const float exposure = 1.5f;
    Result r = run_tonemap(width, height, hdr, exposure);
    CHECK(r.non_finite == 0);
    int exact = 0, off_by_one = 0;
    for (size_t i = 0; i < hdr.size(); ++i) {
        const auto expected = vplkit::reference::tonemap({hdr[i][0], hdr[i][1], hdr[i][2]}, exposure);
        CAPTURE(i);
        for (int c = 0; c < 3; ++c) {
            const double scaled = vplkit::reference::tonemap_channel(hdr[i][c], exposure) * 255.0;
            const bool near_border = std::abs(scaled - std::floor(scaled) - 0.5) < 255.0 * 2e-3;
            const int difference = std::abs(int(r.texels[i][c]) - int(expected[c]));
            if (difference == 0) {
                ++exact;
            } else {
                ++off_by_one;
                CHECK(near_border);
                CHECK(difference == 1);
            }
        }
        CHECK(r.texels[i][3] == 255);
    }
    CHECK(off_by_one * 50 < exact);
    CHECK(r.texels[0][0] == 0);
    CHECK(r.texels[1][0] == 0);
    CHECK(r.texels[1][2] == 255);
}

TEST_CASE("tonemap: non-finite pixels are magenta and counted") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<std::array<float, 4>> hdr = {{nan, 0, 0, 1}, {0.2f, 0.2f, 0.2f, 1}, {0, -inf, 0, 1}, {0, 0, inf, 1}};
    Result r = run_tonemap(2, 2, hdr, 1.0f);
    CHECK(r.non_finite == 3);
    const std::array<uint8_t, 4> magenta = {255, 0, 255, 255};
    CHECK(r.texels[0] == magenta);
    CHECK(r.texels[1] != magenta);
    CHECK(r.texels[2] == magenta);
    CHECK(r.texels[3] == magenta);
}

TEST_CASE("tonemap: a bad exposure is refused") {
    vplkit::Context& ctx = vplkit::test::context();
    auto hdr = vplkit::Image::create(ctx, 2, 2, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "hdr");
    auto ldr = vplkit::Image::create(ctx, 2, 2, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT, "ldr");
    auto stats = vplkit::Buffer::create(ctx, 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    vplkit::PassList passes;
    CHECK_THROWS_WITH_AS(vplkit::stages::add_tonemap_passes(ctx, passes, hdr, ldr, stats, 0.0f),
                         doctest::Contains("exposure must be a positive"), vplkit::Error);
}
