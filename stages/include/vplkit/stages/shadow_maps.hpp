#pragma once
// Shadow maps and reflective shadow maps (RSMs), one per light, rendered in one raster pass per
// light (shaders/raster/rsm_raster.vert + rsm_shade.frag). An RSM texel is the surface patch the
// light reaches through that texel (the thesis section 4.1, chapter 6: the VPL generators sample
// these texels):
//   position  RGBA32F  xyz world position; w = 1 where a surface was drawn, 0 elsewhere
//   normal    RGBA32F  xyz unit shading normal (normal map applied) on the light's side; w = 0
//   flux      RGBA32F  rgb flux the patch reflects diffusely, W (the light's units x m^2 or x sr):
//                      base colour x (1 - metallic) x the light's power through the texel (see
//                      rsm_shade.frag for the derivation); summed over all texels: the power the
//                      surfaces the light reaches reflect diffusely
//   depth     D32      the shadow map: standard depth of the face's projection (0 near .. 1 far,
//                      cleared to 1). No depth bias is baked in: a lookup adds its own.
// Projections, per light type:
//   directional  one orthographic face fitted to the scene's bounds: its x/y extent is the
//                bounds' projection perpendicular to the light, so every texel's beam hits the
//                box and the power of the beams through all texels is the light's power on the
//                scene; depth is linear in distance along the light
//   spot         one perspective face whose square frustum holds the outer cone (field of view
//                2 x outer angle) when the outer angle is at most kSpotSingleFaceMaxAngle; a
//                wider spot is rendered like a point light (its cone falloff still applies)
//   point        a cube map as a 3 x 2 atlas of square faces, +X -X +Y -Y +Z -Z from left to
//                right and top to bottom, each a 90-degree perspective projection
// Every triangle is drawn from both sides, alpha MASK is discarded below the cutoff and BLEND at
// 0.5, as in the G-buffer. The runtime's ShadowMap (vplkit/shadow_map.hpp) fits the faces to a
// light and a scene's bounds, allocates the images and converts to ShadowMapViews.

#include "vplkit/stages/device.hpp"
#include "vplkit/stages/scene_buffers.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <glm/mat4x4.hpp>
#include <vulkan/vulkan.h>

#include <cstdint>
#include <numbers>
#include <span>

namespace vplkit::stages {

inline constexpr VkFormat kRsmPositionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kRsmNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kRsmFluxFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kShadowDepthFormat = VK_FORMAT_D32_SFLOAT;

// Beyond this outer cone angle a spot light gets a cube map (a single perspective face would
// stretch its texels by (1 + tan^2)^(3/2): 8x in solid angle from centre to corner at 60 degrees).
inline constexpr float kSpotSingleFaceMaxAngle = std::numbers::pi_v<float> / 3.0f;

// One face of a light's map.
struct ShadowFace {
    // World -> the face's Vulkan clip space (y down the image, depth 0 .. 1). A world point's
    // texel: ndc = clip.xyz / clip.w, texel = rect.offset + (ndc.xy * 0.5 + 0.5) * rect.extent.
    glm::mat4 view_projection{1.0f};
    VkRect2D rect{};  // the face's texels in the map's images
};

// One light's map as the stages take it. The raster pass writes the four images (colour/depth
// attachment usage, the formats above, one size); BRSM reads position, normal and flux (GENERAL
// layout, storage usage). `faces` is referenced, not copied: it must outlive the recording.
struct ShadowMapViews {
    std::span<const ShadowFace> faces;  // 1, or 6 for a cube map
    ImageView position;
    ImageView normal;
    ImageView flux;
    ImageView depth;
    BufferView light_uniform;  // shaders::RsmLight (uniform usage), read by rsm_shade.frag

    uint32_t width() const { return position.width; }
    uint32_t height() const { return position.height; }
};

// Adds the pass "shadow map <n>" (n = `index`, for timings): reads `scene` and the light
// uniform, clears the images (colours to 0, depth to 1) and draws the scene into every face.
// The scene's draw and texture arrays and the map's faces must stay alive until the steps are
// recorded. Throws Error for a draw whose material has no textures.
void add_shadow_map_pass(Device& device, StepList& passes, const SceneBuffers& scene, const ShadowMapViews& map,
                         uint32_t index = 0);

// One pass per map, in order.
void add_shadow_map_passes(Device& device, StepList& passes, const SceneBuffers& scene,
                           std::span<const ShadowMapViews> maps);

}  // namespace vplkit::stages
