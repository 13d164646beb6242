#pragma once
// The G-buffer adapter (shaders/raster/gbuffer_from_depth.comp): the kit's G-buffer from the
// images a renderer already has, so it needs no second geometry pass. In, per pixel (sampled
// images read with texelFetch: any format whose view the device samples; the view converts
// UNORM, SNORM, sRGB and float to float, so the format is the renderer's choice):
//   depth     the depth as the renderer's projection wrote it, any depth format (D16, D24, D32,
//             with or without stencil: a view of the depth aspect) or a colour copy of it (R32F).
//             Far plane / cleared = 1 (standard Z) or 0 (reversed Z): that pixel is background.
//   normal    the unit shading normal, world or view space (GbufferNormalSpace), in one of
//             the GbufferNormalEncoding layouts (need not be unit: it is normalized).
//   albedo    rgb the linear diffuse base colour (an sRGB format decodes in the view); a unused.
//   material  optional: roughness and metallic in the channels `roughness_channel`,
//             `metallic_channel` (glTF's metallicRoughness: G, B); without it, the constants.
// Out, the kit's G-buffer as vplkit/gbuffer.glsl and gbuffer_views.hpp define it (storage
// images in GENERAL layout, their formats):
//   position          xyz the world position reconstructed from depth at the pixel centre,
//                     moved toward the viewer as the raster pass moves it (at least 2^-16 of
//                     its coordinates and 2 depth resolution steps along the ray, so rays can
//                     start there: gbuffer_shade.frag says why); w = 1 covered, 0 background
//   normal            xyz the decoded shading normal, unit, world space; reversed where it
//                     faces away from both the viewer and the geometric normal (a back face);
//                     w = roughness (perceptual, glTF). A negative roughness
//                     selects the pure Lambertian BRDF base colour / pi (brdf.glsl).
//   geometric_normal  xyz the face normal from depth: the cross product of the tangents to the
//                     right/left and down/up neighbours, each axis the side whose depth differs
//                     less (the other may lie across an edge), turned to the viewer; the shading
//                     normal where a pixel has no covered neighbour on an axis; w = metallic
//   albedo            rgb the albedo image's rgb; a = 1
// Background pixels get 0 in every channel of all four (as the raster pass clears them).
// Emission and depth of GbufferViews are neither read nor written: clear emission to 0 (or
// write the renderer's own emitted radiance) before stages that read it.
//
// Units: albedo is a reflectance in [0, 1]; the kit's BRDF is albedo / pi (radiometric). A
// renderer that shades albedo * N.L uses lights pi times weaker than the kit's for the same image.
//
// A renderer with reversed Z, RG16 SNORM octahedral normals in view space and an sRGB albedo:
//   vplkit::stages::GbufferAdapterOptions o;
//   o.inverse_view_projection = glm::inverse(projection * view);
//   o.depth = vplkit::stages::DepthConvention::reversed;
//   o.normal_encoding = vplkit::stages::GbufferNormalEncoding::octahedral;
//   o.normal_space = vplkit::stages::GbufferNormalSpace::view;
//   o.view_to_world = glm::mat3(glm::inverse(view));
//   o.roughness = vplkit::stages::kLambertianRoughness;  // its materials are Lambertian
//   vplkit::stages::add_gbuffer_adapter_pass(device, steps, {depth, normal, albedo, {}}, o, gbuffer);
// Pixel (x, y) is read at clip x = (x + 0.5) / width * 2 - 1, y = (y + 0.5) / height * 2 - 1
// (Vulkan's viewport: row 0 at clip y = -1). A renderer that flips its viewport (negative height,
// row 0 at clip y = +1) passes inverse(projection * view) * diag(1, -1, 1, 1).

#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <cstdint>

namespace vplkit::stages {

// How the normal image stores a unit vector (the format's conversion is the view's; these say
// what the converted values mean).
enum class GbufferNormalEncoding : uint32_t {
    xyz = 0,               // rgb = n (RGBA32F, RGBA16F, RGBA8/RGBA16 SNORM)
    xyz_unorm = 1,         // rgb = n * 0.5 + 0.5 (RGB10A2 UNORM, RGBA8 UNORM)
    octahedral = 2,        // rg = octahedral(n) in [-1, 1] (RG16 SNORM, RG16F, RG8 SNORM, RG32F)
    octahedral_unorm = 3,  // rg = octahedral(n) * 0.5 + 0.5 (RG16 UNORM, RG8 UNORM)
};
// Octahedral: Cigolle et al. 2014, "A Survey of Efficient Representations for Independent Unit
// Vectors" (JCGT 3(2)), listing 1: e = n.xy / |n|_1, folded over the diagonals where n.z < 0.

enum class GbufferNormalSpace : uint32_t {
    world = 0,
    view = 1,  // rotated to world by GbufferAdapterOptions::view_to_world
};

enum class DepthConvention : uint32_t {
    standard = 0,  // near 0, far 1 (cleared to 1, test LESS): the kit's own convention
    reversed = 1,  // near 1, far 0 (cleared to 0, test GREATER)
};

struct GbufferAdapterInputs {
    ImageView depth;     // sampled; aspect VK_IMAGE_ASPECT_DEPTH_BIT for a depth format
    ImageView normal;    // sampled
    ImageView albedo;    // sampled
    ImageView material;  // sampled, optional (empty: the constants of the options)
};

// The roughness that selects the pure Lambertian BRDF, base colour / pi (any negative value does:
// gbuffer.glsl, brdf.glsl), for a renderer whose surfaces are all diffuse.
inline constexpr float kLambertianRoughness = -1.0f;

struct GbufferAdapterOptions {
    // Vulkan clip space -> world: the inverse of the projection x view the depth was rendered
    // with (clip x right, y down the image, z / w = the stored depth). Perspective or
    // orthographic, any near and far (an infinite far plane too).
    glm::mat4 inverse_view_projection{1.0f};
    DepthConvention depth = DepthConvention::standard;
    GbufferNormalEncoding normal_encoding = GbufferNormalEncoding::xyz;
    GbufferNormalSpace normal_space = GbufferNormalSpace::world;
    // For view-space normals: the camera's rotation, view -> world (the inverse of the view
    // matrix's upper 3x3; its columns are the camera's axes in world space).
    glm::mat3 view_to_world{1.0f};
    // Without a material image: every pixel's roughness (negative: pure Lambert) and metallic.
    float roughness = 1.0f;
    float metallic = 0.0f;
    // With a material image: the channels (0 r, 1 g, 2 b, 3 a) roughness and metallic are in.
    uint32_t roughness_channel = 1;
    uint32_t metallic_channel = 2;
};

// Adds the pass "gbuffer from depth": reads `inputs` (sampled, in SHADER_READ_ONLY_OPTIMAL)
// and writes position, normal, geometric_normal and albedo of `gbuffer` (the formats of
// gbuffer_views.hpp, storage usage, GENERAL). All images one size. The pipeline (one per
// combination of encoding, space, depth convention and channels) is created on first use and
// kept by `device`. Throws Error for mismatched sizes, wrong output formats, a channel above 3, a
// non-finite inverse view-projection or constant.
void add_gbuffer_adapter_pass(Device& device, StepList& passes, const GbufferAdapterInputs& inputs,
                              const GbufferAdapterOptions& options, const GbufferViews& gbuffer);

}  // namespace vplkit::stages
