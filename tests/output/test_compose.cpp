// compose.comp: composed = direct + indirect, checked exactly (one float addition per channel,
// the same on the CPU).

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/compose.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <array>
#include <random>
#include <vector>

using Texel = std::array<float, 4>;

TEST_CASE("compose: direct plus indirect per pixel") {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t width = 21, height = 17;  // not multiples of the 16 x 16 workgroup
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> value(0.0f, 100.0f);
    std::vector<Texel> a(width * height), b(width * height);
    for (size_t i = 0; i < a.size(); ++i) {
        a[i] = {value(rng), value(rng), value(rng), 1.0f};
        b[i] = {value(rng), value(rng), value(rng), 1.0f};
    }
    constexpr VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT;
    auto direct = vplkit::Image::create(ctx, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "direct");
    auto indirect = vplkit::Image::create(ctx, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "indirect");
    auto composed = vplkit::Image::create(ctx, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "composed");
    direct.upload(a);
    indirect.upload(b);
    vplkit::PassList passes("compose test");
    vplkit::stages::add_compose_pass(ctx, passes, direct, indirect, composed);
    passes.run(ctx);
    const auto out = composed.download<Texel>();
    for (size_t i = 0; i < out.size(); ++i) {
        CAPTURE(i);
        for (int c = 0; c < 3; ++c) CHECK(out[i][c] == a[i][c] + b[i][c]);
        CHECK(out[i][3] == 1.0f);
    }
}

TEST_CASE("compose: images of different sizes are refused") {
    vplkit::Context& ctx = vplkit::test::context();
    constexpr VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT;
    auto direct = vplkit::Image::create(ctx, 4, 4, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "direct");
    auto indirect = vplkit::Image::create(ctx, 4, 5, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "small indirect");
    auto composed = vplkit::Image::create(ctx, 4, 4, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "composed");
    vplkit::PassList passes;
    CHECK_THROWS_WITH_AS(vplkit::stages::add_compose_pass(ctx, passes, direct, indirect, composed),
                         doctest::Contains("'small indirect' must be RGBA32F and of the frame's size"), vplkit::Error);
}
