// compose.comp: composed = direct + indirect, checked exactly (one float addition per channel,
// the same on the CPU); compose_rgba16f.comp and compose_rgba8.comp against the RGBA32F result
// within the format's precision (a half's last place, half a UNORM step), in place too.

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/compose.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
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
                         doctest::Contains("'small indirect' must be of the frame's size (4x4)"), vplkit::Error);
    auto half = vplkit::Image::create(ctx, 4, 4, VK_FORMAT_R16G16B16A16_SFLOAT, storage, "half direct");
    auto srgb = vplkit::Image::create(ctx, 4, 4, VK_FORMAT_R8G8B8A8_SRGB, VK_IMAGE_USAGE_SAMPLED_BIT, "srgb");
    CHECK_THROWS_WITH_AS(vplkit::stages::add_compose_pass(ctx, passes, half, composed, composed),
                         doctest::Contains("'half direct' must be of the format of 'composed'"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::stages::add_compose_pass(ctx, passes, composed, half, composed),
                         doctest::Contains("'half direct' must be RGBA32F"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::stages::add_compose_pass(ctx, passes, srgb, composed, srgb),
                         doctest::Contains("'srgb' must be RGBA32F, RGBA16F or RGBA8 UNORM"), vplkit::Error);
}

namespace {

// The values the format holds (what an upload of `t` stores, read back as floats).
Texel quantized(const Texel& t, VkFormat format) {
    Texel q = t;
    for (float& c : q) {
        if (format == VK_FORMAT_R16G16B16A16_SFLOAT) c = glm::unpackHalf1x16(glm::packHalf1x16(c));
        if (format == VK_FORMAT_R8G8B8A8_UNORM) c = std::round(std::clamp(c, 0.0f, 1.0f) * 255.0f) / 255.0f;
    }
    return q;
}

// Uploads `texels` (quantized to `format`) into `image`.
void upload(vplkit::Image& image, const std::vector<Texel>& texels) {
    if (image.format() == VK_FORMAT_R32G32B32A32_SFLOAT) return image.upload(texels);
    if (image.format() == VK_FORMAT_R16G16B16A16_SFLOAT) {
        std::vector<std::array<uint16_t, 4>> half(texels.size());
        for (size_t i = 0; i < texels.size(); ++i)
            for (int c = 0; c < 4; ++c) half[i][c] = glm::packHalf1x16(texels[i][c]);
        return image.upload(half);
    }
    std::vector<std::array<uint8_t, 4>> unorm(texels.size());
    for (size_t i = 0; i < texels.size(); ++i)
        for (int c = 0; c < 4; ++c)
            unorm[i][c] = uint8_t(std::lround(quantized(texels[i], image.format())[c] * 255.0f));
    image.upload(unorm);
}

std::vector<Texel> download(vplkit::Image& image) {
    if (image.format() == VK_FORMAT_R32G32B32A32_SFLOAT) return image.download<Texel>();
    std::vector<Texel> out;
    if (image.format() == VK_FORMAT_R16G16B16A16_SFLOAT) {
        for (const auto& h : image.download<std::array<uint16_t, 4>>()) {
            out.push_back({glm::unpackHalf1x16(h[0]), glm::unpackHalf1x16(h[1]), glm::unpackHalf1x16(h[2]),
                           glm::unpackHalf1x16(h[3])});
        }
        return out;
    }
    for (const auto& u : image.download<std::array<uint8_t, 4>>())
        out.push_back({u[0] / 255.0f, u[1] / 255.0f, u[2] / 255.0f, u[3] / 255.0f});
    return out;
}

}  // namespace

TEST_CASE("compose: into RGBA16F and RGBA8 UNORM, as the RGBA32F result within the format's precision") {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t width = 19, height = 18;
    constexpr VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT;
    const VkFormat rgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;
    for (VkFormat format : {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM}) {
        CAPTURE(format);
        const bool unorm = format == VK_FORMAT_R8G8B8A8_UNORM;
        std::mt19937 rng(9);
        // UNORM: sums up to 1.3, so the clamp at 1 is met; half: radiance across decades.
        std::uniform_real_distribution<float> value(0.0f, unorm ? 0.65f : 1.0f);
        std::uniform_real_distribution<float> decade(-3.0f, 3.0f);
        std::vector<Texel> direct(width * height), indirect(width * height);
        for (size_t i = 0; i < direct.size(); ++i) {
            for (int c = 0; c < 3; ++c) {
                direct[i][c] = unorm ? value(rng) : value(rng) * std::pow(10.0f, decade(rng));
                indirect[i][c] = unorm ? value(rng) : value(rng) * std::pow(10.0f, decade(rng));
            }
            direct[i][3] = indirect[i][3] = 1.0f;
            direct[i] = quantized(direct[i], format);  // both paths start from what the format holds
        }
        // The reference: the same sums in RGBA32F.
        auto direct32 = vplkit::Image::create(ctx, width, height, rgba32f, storage, "direct32");
        auto indirect32 = vplkit::Image::create(ctx, width, height, rgba32f, storage, "indirect");
        auto composed32 = vplkit::Image::create(ctx, width, height, rgba32f, storage, "composed32");
        auto direct_f = vplkit::Image::create(ctx, width, height, format, storage, "direct");
        auto composed_f = vplkit::Image::create(ctx, width, height, format, storage, "composed");
        auto in_place = vplkit::Image::create(ctx, width, height, format, storage, "colour target");
        upload(direct32, direct);
        upload(indirect32, indirect);
        upload(direct_f, direct);
        upload(in_place, direct);
        vplkit::PassList passes("compose formats test");
        vplkit::stages::add_compose_pass(ctx, passes, direct32, indirect32, composed32);
        vplkit::stages::add_compose_pass(ctx, passes, direct_f, indirect32, composed_f);
        vplkit::stages::add_compose_pass(ctx, passes, in_place, indirect32, in_place);
        passes.run(ctx);
        const std::vector<Texel> reference = download(composed32), got = download(composed_f),
                                 added = download(in_place);
        for (size_t i = 0; i < reference.size(); ++i) {
            CAPTURE(i);
            for (int c = 0; c < 4; ++c) {
                // Half: one unit in the last place (Vulkan lets the store round to nearest or toward
                // zero), 2^-10 relative, 2^-24 among the subnormals; UNORM: clamp, then half a step.
                const float expected = unorm ? std::clamp(reference[i][c], 0.0f, 1.0f) : reference[i][c];
                const float tolerance = unorm ? 0.5f / 255.0f + 1e-6f : std::abs(expected) * 0x1p-10f + 0x1p-24f;
                CHECK(std::abs(got[i][c] - expected) <= tolerance);
                CHECK(added[i][c] == got[i][c]);
            }
        }
    }
}
