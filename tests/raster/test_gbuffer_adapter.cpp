// The G-buffer adapter (shaders/raster/gbuffer_from_depth.comp, stages/gbuffer_adapter.hpp) on
// lavapipe: the in-repo Cornell box's own G-buffer (the raster pass, as the runtime renders it)
// gives the depth, normals and albedo a foreign renderer would have; each is encoded on the CPU as
// a renderer would store it, fed through the adapter, and the result compared per pixel with the
// kit's G-buffer and with a double-precision reconstruction (tests/reference/
// gbuffer_adapter_reference.cpp) from the same depth.
//
// Reversed Z: a renderer with reversed Z stores 1 - d where the kit stores d (its projection's
// clip z is w - z); 1 - d is exact in float for d in [0.5, 1], so the reversed input carries the
// same information, and the inverse is inverse(view_projection) x R (R: z -> w - z, its own inverse).
//
// Tolerances (per pixel; `dpd` = |d position / d depth| there, from the reference):
//   coverage                  identical
//   position vs reference     2^-24 x dpd (one D32 step as a distance: the float unprojection of
//                             the same depth rounds to less) + 1e-6 x |p| (float coordinates)
//   position vs kit           the above + 4 x 2^-24 x dpd (the raster depth is the interpolated
//                             z/w rounded to D32, off by up to a few ulps from the interpolated
//                             position) + 2^-16 x the scene's largest coordinate (the raster pass
//                             pulls by its triangle's corner magnitude, the adapter by its point's)
//   normal vs kit             per encoding: float32 1e-6; float16 1e-3 (2^-12 per component,
//                             x sqrt(3), x 2 for renormalization); RGB10A2 3.4e-3 (1/1023 per
//                             component, same factors); octahedral RG16 SNORM 2e-4 (2^-16 per
//                             component, the decode's slope <= 2 and renormalization <= sqrt(3),
//                             x 2); octahedral RG16F 2e-3 (2^-12 per component, same factors);
//                             octahedral RG8 UNORM 3e-2 (1/255 per component, same factors)
//   geometric normal vs kit   5e-3 away from edges (measured at most 7.3e-4 on this box): two depth
//                             ulps at each end of a tangent one pixel long
//   D16 depth                 positions also within 2.5 levels x dpd of the kit's (half a level
//                             of rounding, the adapter's pull of 2 levels); geometric normals
//                             0.2 (measured 0.06): half a level is ~2e-3 of distance at the back
//                             wall, over a tangent of ~0.05 (a pixel there), at both ends and for
//                             both tangents
//   roughness, metallic       exact from constants; 1e-6 from an RGBA8 UNORM image (k / 255)
//   albedo                    exact from RGBA16F and RGBA32F (the kit's RGBA16F values); from
//                             RGBA8 UNORM: code / 255 within 2^-10 relative (RGBA16F out); from
//                             sRGB8: the code's exact decode within 1e-3 relative (RGBA16F out)
//                             + 1.5e-3 (lavapipe's sRGB decode, measured in test_gbuffer.cpp)

#include "gbuffer_adapter_reference.hpp"
#include "raster_test_scenes.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit/stages/gbuffer_adapter.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using vplkit::stages::DepthConvention;
using vplkit::stages::GbufferNormalEncoding;
using vplkit::stages::GbufferNormalSpace;

constexpr uint32_t kWidth = 64, kHeight = 48;
// The albedo formats a renderer stores its base colour in.
constexpr VkFormat kSrgbAlbedo = VK_FORMAT_R8G8B8A8_SRGB, kUnormAlbedo = VK_FORMAT_R8G8B8A8_UNORM,
                   kHalfAlbedo = VK_FORMAT_R16G16B16A16_SFLOAT, kFloatAlbedo = VK_FORMAT_R32G32B32A32_SFLOAT;

struct KitGbuffer {
    std::vector<glm::vec4> position, normal, geometric_normal, albedo;
    std::vector<float> depth;
    vplkit::stages::CameraView view;
    glm::dmat3 view_to_world{1.0};
    double max_coordinate = 0.0;
};

const KitGbuffer& kit_gbuffer(vplkit::Context& ctx) {
    static const KitGbuffer kit = [&ctx] {
        raster_test::RolledCornellGbuffer g = raster_test::rolled_cornell_gbuffer(ctx, kWidth, kHeight);
        KitGbuffer k;
        k.view = g.view;
        k.view_to_world = glm::dmat3(g.view_to_world);
        const glm::vec3 corner = glm::max(glm::abs(g.bounds_min), glm::abs(g.bounds_max));
        k.max_coordinate = std::max({corner.x, corner.y, corner.z});
        k.position = std::move(g.position);
        k.normal = std::move(g.normal);
        k.geometric_normal = std::move(g.geometric_normal);
        k.albedo = std::move(g.albedo);
        k.depth = std::move(g.depth);
        return k;
    }();
    return kit;
}

struct AdapterCase {
    const char* name;
    GbufferNormalEncoding encoding;
    VkFormat normal_format;
    GbufferNormalSpace space;
    DepthConvention depth;
    VkFormat albedo_format;  // sRGB8, UNORM8, RGBA16F or RGBA32F
    bool material_image;
    double normal_bound;
    bool d16_depth = false;  // else D32
    double geometric_bound = 5e-3;
};

template <class T>
void put(std::vector<uint8_t>& bytes, size_t at, T value) {
    std::memcpy(bytes.data() + at, &value, sizeof(T));
}

uint32_t texel_bytes(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return 16;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
            return 8;
        case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
        case VK_FORMAT_R16G16_SNORM:
        case VK_FORMAT_R16G16_SFLOAT:
            return 4;
        case VK_FORMAT_R8G8_UNORM:
            return 2;
        default:
            FAIL("unexpected normal format");
            return 0;
    }
}

// The kit's world normal as the renderer's normal image would hold it.
std::vector<uint8_t> encode_normals(const KitGbuffer& kit, const AdapterCase& c) {
    const uint32_t stride = texel_bytes(c.normal_format);
    std::vector<uint8_t> bytes(size_t(kWidth) * kHeight * stride, 0);
    for (size_t i = 0; i < kit.normal.size(); ++i) {
        glm::dvec3 n(kit.normal[i]);
        if (c.space == GbufferNormalSpace::view) n = glm::transpose(kit.view_to_world) * n;
        const size_t at = i * stride;
        const auto unorm = [](double x, double levels) {
            return std::lround(std::clamp(x * 0.5 + 0.5, 0.0, 1.0) * levels);
        };
        switch (c.normal_format) {
            case VK_FORMAT_R32G32B32A32_SFLOAT:
                put(bytes, at, glm::vec4(glm::vec3(n), 0.0f));
                break;
            case VK_FORMAT_R16G16B16A16_SFLOAT:
                for (int k = 0; k < 3; ++k) put(bytes, at + 2 * k, glm::packHalf1x16(float(n[k])));
                break;
            case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
                put(bytes, at, uint32_t(unorm(n.x, 1023) | unorm(n.y, 1023) << 10 | unorm(n.z, 1023) << 20 | 3u << 30));
                break;
            case VK_FORMAT_R16G16_SNORM: {
                const glm::dvec2 e = vplkit::reference::octahedral_encode(n);
                for (int k = 0; k < 2; ++k)
                    put(bytes, at + 2 * k, int16_t(std::lround(std::clamp(e[k], -1.0, 1.0) * 32767)));
                break;
            }
            case VK_FORMAT_R16G16_SFLOAT: {
                const glm::dvec2 e = vplkit::reference::octahedral_encode(n);
                for (int k = 0; k < 2; ++k) put(bytes, at + 2 * k, glm::packHalf1x16(float(e[k])));
                break;
            }
            case VK_FORMAT_R8G8_UNORM: {
                const glm::dvec2 e = vplkit::reference::octahedral_encode(n);
                for (int k = 0; k < 2; ++k) put(bytes, at + k, uint8_t(unorm(e[k], 255)));
                break;
            }
            default:
                break;
        }
    }
    return bytes;
}

double srgb_to_linear(double s) {
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

uint8_t linear_to_srgb_code(double x) {
    x = std::clamp(x, 0.0, 1.0);
    const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
    return uint8_t(std::lround(s * 255.0));
}

double distance(glm::vec3 a, glm::dvec3 b) {
    return glm::length(glm::dvec3(a) - b);
}

// The pixel and its 8 neighbours lie on one plane of the kit's G-buffer (same face normal, same
// plane offset): the geometric normal from depth is determined there.
bool away_from_edges(const KitGbuffer& kit, int px, int py) {
    if (px < 1 || py < 1 || px >= int(kWidth) - 1 || py >= int(kHeight) - 1) return false;
    const size_t i = size_t(py) * kWidth + px;
    const glm::vec3 g(kit.geometric_normal[i]);
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            const size_t j = size_t(py + dy) * kWidth + (px + dx);
            if (kit.position[j].w != 1.0f) return false;
            if (glm::length(glm::vec3(kit.geometric_normal[j]) - g) > 1e-6f) return false;
            if (std::abs(glm::dot(g, glm::vec3(kit.position[j]) - glm::vec3(kit.position[i]))) > 1e-3f) return false;
        }
    }
    return true;
}

}  // namespace

TEST_CASE("gbuffer adapter: depth, normals and albedo in a renderer's encodings give the kit's G-buffer") {
    vplkit::Context& ctx = vplkit::test::context();
    const KitGbuffer& kit = kit_gbuffer(ctx);

    const AdapterCase cases[] = {
        {"xyz RGBA32F world, standard Z, RGBA32F albedo", GbufferNormalEncoding::xyz, VK_FORMAT_R32G32B32A32_SFLOAT,
         GbufferNormalSpace::world, DepthConvention::standard, kFloatAlbedo, false, 1e-6},
        {"xyz RGBA16F view, reversed Z, sRGB albedo, material image", GbufferNormalEncoding::xyz,
         VK_FORMAT_R16G16B16A16_SFLOAT, GbufferNormalSpace::view, DepthConvention::reversed, kSrgbAlbedo, true, 1e-3},
        {"RGB10A2 world, standard Z, RGBA8 UNORM albedo", GbufferNormalEncoding::xyz_unorm,
         VK_FORMAT_A2B10G10R10_UNORM_PACK32, GbufferNormalSpace::world, DepthConvention::standard, kUnormAlbedo, false,
         3.4e-3},
        {"octahedral RG16 SNORM view, reversed Z", GbufferNormalEncoding::octahedral, VK_FORMAT_R16G16_SNORM,
         GbufferNormalSpace::view, DepthConvention::reversed, kHalfAlbedo, false, 2e-4},
        {"octahedral RG16F world, standard Z, material image", GbufferNormalEncoding::octahedral,
         VK_FORMAT_R16G16_SFLOAT, GbufferNormalSpace::world, DepthConvention::standard, kHalfAlbedo, true, 2e-3},
        {"octahedral RG8 UNORM world, reversed Z", GbufferNormalEncoding::octahedral_unorm, VK_FORMAT_R8G8_UNORM,
         GbufferNormalSpace::world, DepthConvention::reversed, kSrgbAlbedo, false, 3e-2},
        {"octahedral RG16 SNORM world, D16 depth, standard Z", GbufferNormalEncoding::octahedral,
         VK_FORMAT_R16G16_SNORM, GbufferNormalSpace::world, DepthConvention::standard, kHalfAlbedo, false, 2e-4, true,
         0.2},
    };
    const glm::dmat4 view_projection(kit.view.view_projection);
    glm::dmat4 reverse(1.0);  // clip z -> w - z
    reverse[2][2] = -1.0;
    reverse[3][2] = 1.0;

    for (const AdapterCase& c : cases) {
        const std::string case_name = c.name;
        CAPTURE(case_name);
        const bool reversed = c.depth == DepthConvention::reversed;
        const glm::dmat4 inverse = glm::inverse(reversed ? reverse * view_projection : view_projection);

        std::vector<float> depth(kit.depth);
        if (reversed) {
            for (float& d : depth) d = 1.0f - d;
        }
        // D16: the kit's depth rounded to the nearest of its 65,536 levels; `depth` the value read.
        const double quantum = c.d16_depth ? 1.0 / 65535.0 : 0.0;
        auto depth_image =
            vplkit::Image::create(ctx, kWidth, kHeight, c.d16_depth ? VK_FORMAT_D16_UNORM : VK_FORMAT_D32_SFLOAT,
                                  VK_IMAGE_USAGE_SAMPLED_BIT, "renderer depth");
        if (c.d16_depth) {
            std::vector<uint16_t> codes(depth.size());
            for (size_t i = 0; i < depth.size(); ++i) {
                codes[i] = uint16_t(std::lround(double(depth[i]) * 65535.0));
                depth[i] = float(codes[i] / 65535.0);
            }
            depth_image.upload(codes);
        } else {
            depth_image.upload(depth);
        }
        auto normal_image =
            vplkit::Image::create(ctx, kWidth, kHeight, c.normal_format, VK_IMAGE_USAGE_SAMPLED_BIT, "renderer normal");
        const std::vector<uint8_t> normal_bytes = encode_normals(kit, c);
        normal_image.upload(normal_bytes.data(), normal_bytes.size());

        // The kit's albedo as the renderer's image holds it; `expected_albedo` the value stored.
        std::vector<glm::dvec3> expected_albedo(kit.albedo.size());
        std::vector<uint8_t> albedo_bytes;
        for (size_t i = 0; i < kit.albedo.size(); ++i) {
            for (int k = 0; k < 4; ++k) {
                const float a = kit.albedo[i][k];
                double stored = a;
                if (c.albedo_format == kSrgbAlbedo || c.albedo_format == kUnormAlbedo) {
                    const uint8_t code = k == 3                           ? uint8_t(255)
                                         : c.albedo_format == kSrgbAlbedo ? linear_to_srgb_code(a)
                                                                          : uint8_t(std::lround(a * 255.0));
                    albedo_bytes.push_back(code);
                    stored = c.albedo_format == kSrgbAlbedo ? srgb_to_linear(code / 255.0) : code / 255.0;
                } else if (c.albedo_format == kHalfAlbedo) {
                    const uint16_t half = glm::packHalf1x16(a);
                    albedo_bytes.resize(albedo_bytes.size() + 2);
                    std::memcpy(albedo_bytes.data() + albedo_bytes.size() - 2, &half, 2);
                    stored = glm::unpackHalf1x16(half);
                } else {
                    albedo_bytes.resize(albedo_bytes.size() + 4);
                    std::memcpy(albedo_bytes.data() + albedo_bytes.size() - 4, &a, 4);
                }
                if (k < 3) expected_albedo[i][k] = stored;
            }
        }
        auto albedo_image =
            vplkit::Image::create(ctx, kWidth, kHeight, c.albedo_format, VK_IMAGE_USAGE_SAMPLED_BIT, "renderer albedo");
        albedo_image.upload(albedo_bytes.data(), albedo_bytes.size());

        // Roughness in alpha, metallic in red: channels other than glTF's G, B.
        constexpr uint8_t kRoughnessCode = 51, kMetallicCode = 204;
        vplkit::Image material_image;
        if (c.material_image) {
            std::vector<uint8_t> texels(kit.albedo.size() * 4, 0);
            for (size_t i = 0; i < kit.albedo.size(); ++i) {
                texels[4 * i + 0] = kMetallicCode;
                texels[4 * i + 3] = kRoughnessCode;
            }
            material_image = vplkit::Image::create(ctx, kWidth, kHeight, VK_FORMAT_R8G8B8A8_UNORM,
                                                   VK_IMAGE_USAGE_SAMPLED_BIT, "renderer material");
            material_image.upload(texels);
        }

        vplkit::stages::GbufferAdapterOptions options;
        options.inverse_view_projection = glm::mat4(inverse);
        options.depth = c.depth;
        options.normal_encoding = c.encoding;
        options.normal_space = c.space;
        options.view_to_world = glm::mat3(kit.view_to_world);
        options.roughness = 1.0f;  // the Cornell box's materials
        options.metallic = 0.0f;
        options.roughness_channel = 3;
        options.metallic_channel = 0;
        vplkit::stages::GbufferAdapterInputs inputs{
            depth_image, normal_image, albedo_image,
            c.material_image ? vplkit::ImageView(material_image) : vplkit::ImageView{}};
        auto out = vplkit::GbufferImages::create(ctx, kWidth, kHeight);
        vplkit::PassList passes("gbuffer adapter");
        vplkit::stages::add_gbuffer_adapter_pass(ctx, passes, inputs, options, out);
        passes.run(ctx);
        const std::vector<glm::vec4> position = raster_test::download_rgba(out.position);
        const std::vector<glm::vec4> normal = raster_test::download_rgba(out.normal);
        const std::vector<glm::vec4> geometric_normal = raster_test::download_rgba(out.geometric_normal);
        const std::vector<glm::vec4> albedo = raster_test::download_rgba(out.albedo);

        int covered = 0, interior = 0;
        double worst_position_kit = 0.0, worst_normal = 0.0, worst_geometric = 0.0;
        for (uint32_t py = 0; py < kHeight; ++py) {
            for (uint32_t px = 0; px < kWidth; ++px) {
                const size_t i = size_t(py) * kWidth + px;
                CAPTURE(px);
                CAPTURE(py);
                REQUIRE(position[i].w == kit.position[i].w);
                if (kit.position[i].w == 0.0f) {
                    CHECK(position[i] == glm::vec4(0.0f));
                    CHECK(normal[i] == glm::vec4(0.0f));
                    CHECK(geometric_normal[i] == glm::vec4(0.0f));
                    CHECK(albedo[i] == glm::vec4(0.0f));
                    continue;
                }
                ++covered;
                const auto reference =
                    vplkit::reference::point_from_depth(inverse, depth[i], quantum, px, py, kWidth, kHeight, reversed);
                const double depth_step = std::ldexp(1.0, -24) * reference.distance_per_depth;
                const double reference_bound = 2.0 * depth_step + 1e-6 * glm::length(reference.surface);
                CHECK(distance(glm::vec3(position[i]), reference.position) <= reference_bound);
                const double kit_error = distance(glm::vec3(position[i]), glm::dvec3(glm::vec3(kit.position[i])));
                worst_position_kit = std::max(
                    worst_position_kit, kit_error / glm::length(reference.surface - glm::dvec3(kit.view.position)));
                // D16 adds half a level of rounding and a pull of 2 levels (the kit's is 2^-22 d).
                const double quantum_distance = 2.5 * quantum * reference.distance_per_depth;
                CHECK(kit_error <=
                      reference_bound + 4.0 * depth_step + std::ldexp(kit.max_coordinate, -16) + quantum_distance);

                const double normal_error = distance(glm::vec3(normal[i]), glm::dvec3(glm::vec3(kit.normal[i])));
                worst_normal = std::max(worst_normal, normal_error);
                CHECK(normal_error <= c.normal_bound);

                const glm::vec3 g(geometric_normal[i]);
                CHECK(std::abs(glm::length(g) - 1.0f) < 1e-5f);
                CHECK(glm::dot(glm::dvec3(g), reference.to_viewer) > 0.0);
                if (away_from_edges(kit, int(px), int(py))) {
                    ++interior;
                    const double g_error = distance(g, glm::dvec3(glm::vec3(kit.geometric_normal[i])));
                    worst_geometric = std::max(worst_geometric, g_error);
                    CHECK(g_error <= c.geometric_bound);
                    CHECK(glm::dot(glm::vec3(normal[i]), g) >= 0.0f);
                }

                if (c.material_image) {
                    CHECK(std::abs(normal[i].w - kRoughnessCode / 255.0) <= 1e-6);
                    CHECK(std::abs(geometric_normal[i].w - kMetallicCode / 255.0) <= 1e-6);
                } else {
                    CHECK(normal[i].w == kit.normal[i].w);
                    CHECK(geometric_normal[i].w == kit.geometric_normal[i].w);
                }
                for (int k = 0; k < 3; ++k) {
                    CAPTURE(k);
                    // sRGB: lavapipe's decode within 1.5e-3 of the exact one (test_gbuffer.cpp);
                    // UNORM: code / 255 to the kit's RGBA16F, within one half step (2^-10 relative:
                    // lavapipe's storage-image conversion truncates, not rounds); half and
                    // float (values the kit's RGBA16F held): exact.
                    const double bound = c.albedo_format == kSrgbAlbedo    ? 1e-3 * expected_albedo[i][k] + 1.5e-3
                                         : c.albedo_format == kUnormAlbedo ? std::ldexp(expected_albedo[i][k], -10)
                                                                           : 0.0;
                    CHECK(std::abs(albedo[i][k] - expected_albedo[i][k]) <= bound);
                }
                CHECK(albedo[i].w == 1.0f);
            }
        }
        MESSAGE(case_name << ": worst position vs kit " << worst_position_kit << " of the distance, normal "
                          << worst_normal << ", geometric normal " << worst_geometric << " over " << interior
                          << " interior of " << covered << " covered pixels");
        CHECK(covered > int(kWidth * kHeight) / 2);
        CHECK(interior > covered / 2);
        // The bar: positions within 1e-4 relative to the distance from the camera (D32).
        if (!c.d16_depth) CHECK(worst_position_kit <= 1e-4);
    }
}

TEST_CASE("gbuffer adapter: inconsistent images and options are refused with a message") {
    vplkit::Context& ctx = vplkit::test::context();
    auto sampled = [&ctx](uint32_t w, uint32_t h, VkFormat format, const char* name) {
        return vplkit::Image::create(ctx, w, h, format, VK_IMAGE_USAGE_SAMPLED_BIT, name);
    };
    auto depth = sampled(8, 8, VK_FORMAT_D32_SFLOAT, "depth");
    auto normal = sampled(8, 8, VK_FORMAT_R16G16_SNORM, "normal");
    auto albedo = sampled(8, 8, VK_FORMAT_R8G8B8A8_SRGB, "albedo");
    auto small_albedo = sampled(4, 8, VK_FORMAT_R8G8B8A8_SRGB, "small albedo");
    auto out = vplkit::GbufferImages::create(ctx, 8, 8);
    vplkit::PassList passes("gbuffer adapter refusals");
    vplkit::stages::GbufferAdapterOptions options;
    const vplkit::stages::GbufferViews gbuffer = out;
    CHECK_THROWS_WITH_AS(
        vplkit::stages::add_gbuffer_adapter_pass(ctx, passes, {depth, normal, small_albedo, {}}, options, gbuffer),
        doctest::Contains("'small albedo' is 4x8"), vplkit::Error);
    vplkit::stages::GbufferViews wrong_albedo = gbuffer;
    wrong_albedo.albedo = albedo;
    CHECK_THROWS_WITH_AS(
        vplkit::stages::add_gbuffer_adapter_pass(ctx, passes, {depth, normal, albedo, {}}, options, wrong_albedo),
        doctest::Contains("'albedo' has format"), vplkit::Error);
    options.metallic_channel = 4;
    CHECK_THROWS_WITH_AS(
        vplkit::stages::add_gbuffer_adapter_pass(ctx, passes, {depth, normal, albedo, {}}, options, gbuffer),
        doctest::Contains("is not 0..3"), vplkit::Error);
    CHECK(passes.steps().empty());
}
