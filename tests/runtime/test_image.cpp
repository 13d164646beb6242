// Images: whole-image upload/download round trips for the formats stages use (odd extents
// included), layout tracking, and the errors a caller can make.

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

using vplkit::Image;

namespace {

template <class T>
std::vector<T> ramp(size_t count, T scale) {
    std::vector<T> values(count);
    for (size_t i = 0; i < count; ++i) values[i] = T(i) * scale;
    return values;
}

}  // namespace

TEST_CASE("image round trip: R32_SFLOAT - odd extent") {
    vplkit::Context& ctx = vplkit::test::context();
    auto image = Image::create(ctx, 7, 5, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "r32f");
    CHECK(image.texel_bytes() == 4);
    CHECK(image.byte_size() == 7 * 5 * 4);
    CHECK(image.view() != VK_NULL_HANDLE);
    CHECK(image.layout() == VK_IMAGE_LAYOUT_UNDEFINED);
    const auto texels = ramp<float>(35, 0.25f);
    image.upload(texels);
    CHECK(image.layout() == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    CHECK(image.download<float>() == texels);
    CHECK(image.layout() == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

TEST_CASE("image round trip: RGBA8 - RGBA16F bits - RGBA32F - RG32UI") {
    vplkit::Context& ctx = vplkit::test::context();
    {
        auto image = Image::create(ctx, 13, 3, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, "rgba8");
        std::vector<uint8_t> texels(13 * 3 * 4);
        for (size_t i = 0; i < texels.size(); ++i) texels[i] = uint8_t(i * 37);
        image.upload(texels);
        CHECK(image.download<uint8_t>() == texels);
    }
    {
        // Half floats go through as raw 16-bit patterns (no conversion on copies).
        auto image = Image::create(ctx, 4, 9, VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "rgba16f");
        const auto texels = ramp<uint16_t>(4 * 9 * 4, 97);
        image.upload(texels);
        CHECK(image.download<uint16_t>() == texels);
    }
    {
        auto image = Image::create(ctx, 16, 16, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "rgba32f");
        const auto texels = ramp<float>(16 * 16 * 4, -1.5f);
        image.upload(texels);
        CHECK(image.download<float>() == texels);
    }
    {
        auto image = Image::create(ctx, 1, 1, VK_FORMAT_R32G32_UINT, VK_IMAGE_USAGE_STORAGE_BIT, "rg32ui");
        const std::vector<uint32_t> texels = {0xdeadbeefu, 42u};
        image.upload(texels);
        CHECK(image.download<uint32_t>() == texels);
    }
}

TEST_CASE("image round trip: depth") {
    vplkit::Context& ctx = vplkit::test::context();
    auto image = Image::create(ctx, 5, 3, VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "depth");
    CHECK(image.aspect() == VK_IMAGE_ASPECT_DEPTH_BIT);
    const auto texels = ramp<float>(15, 1.0f / 16.0f);  // depth copies keep values in [0, 1]
    image.upload(texels);
    CHECK(image.download<float>() == texels);
}

TEST_CASE("transition records a barrier and tracks the layout") {
    vplkit::Context& ctx = vplkit::test::context();
    auto image = Image::create(ctx, 8, 8, VK_FORMAT_R32_UINT, VK_IMAGE_USAGE_STORAGE_BIT, "transition");
    ctx.one_shot([&](VkCommandBuffer cmd) {
        image.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkClearColorValue value{.uint32 = {9u, 0u, 0u, 0u}};
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1, &range);
        image.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    });
    CHECK(image.layout() == VK_IMAGE_LAYOUT_GENERAL);
    CHECK(image.download<uint32_t>() == std::vector<uint32_t>(64, 9u));
}

TEST_CASE("image misuse is a clear error") {
    vplkit::Context& ctx = vplkit::test::context();
    auto image = Image::create(ctx, 4, 4, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "sized");
    const std::vector<float> wrong(15);
    CHECK_THROWS_WITH_AS(image.upload(wrong), doctest::Contains("needs exactly 64 bytes"), vplkit::Error);
    CHECK_THROWS_WITH_AS(Image::create(ctx, 0, 4, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "flat"),
                         doctest::Contains("empty extent"), vplkit::Error);
    // A compressed format is never a color attachment.
    CHECK_THROWS_WITH_AS(
        Image::create(ctx, 4, 4, VK_FORMAT_BC1_RGB_UNORM_BLOCK, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "bc1"),
        doctest::Contains("is not supported by"), vplkit::Error);
    CHECK(vplkit::format_name(VK_FORMAT_R16G16_SFLOAT) == "VK_FORMAT_R16G16_SFLOAT");
}

TEST_CASE("images move") {
    vplkit::Context& ctx = vplkit::test::context();
    auto a = Image::create(ctx, 2, 2, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, "moved");
    const VkImage handle = a.handle();
    Image b = std::move(a);
    CHECK(b.handle() == handle);
    CHECK(!a);
    CHECK(b.extent().width == 2);
}
