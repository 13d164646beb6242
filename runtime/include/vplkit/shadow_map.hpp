#pragma once
// The runtime's shadow map / RSM of one light (stages/shadow_maps.hpp): its faces fitted to the
// light and the scene's bounds, the images and the light's uniform, converting to the
// ShadowMapViews the stages take.

#include "vplkit/buffer.hpp"
#include "vplkit/image.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"
#include "vplkit/stages/shadow_maps.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vplkit {
class Context;
}  // namespace vplkit

namespace vplkit {

struct ShadowMap {
    scene::Light light;
    uint32_t face_resolution = 0;           // texels along a face's side
    std::vector<stages::ShadowFace> faces;  // 1, or 6 for a cube map
    // Where depth is 0 and 1: distance from the light along the face's axis (point, spot), or
    // signed distance along the light from the bounds' centre (directional; depth is linear).
    float near_plane = 0.0f;
    float far_plane = 0.0f;
    float texel_area = 0.0f;  // directional: one texel's beam cross-section (m^2); else 0
    Image position;
    Image normal;
    Image flux;
    Image depth;
    Buffer light_uniform;  // shaders::RsmLight, read by rsm_shade.frag

    // Images of face_resolution x face_resolution (3 x 2 faces for a cube map) with colour/depth
    // attachment, storage (colour) and sampled usage. `bounds` is the scene's (GpuScene::bounds()):
    // the directional fit and every light's near and far planes come from it. Throws Error for a
    // zero resolution, a light with a non-finite or zero direction, or a negative intensity.
    static ShadowMap create(Context& context, const scene::Light& light, const scene::Bounds& bounds,
                            uint32_t face_resolution);

    uint32_t width() const { return position.width(); }
    uint32_t height() const { return position.height(); }

    // As the stages take it; layouts stay tracked in these Images, the faces in this object.
    operator stages::ShadowMapViews() { return {faces, position, normal, flux, depth, light_uniform}; }
};

// The maps as the stages take them (views of each, in order).
std::vector<stages::ShadowMapViews> shadow_map_views(std::span<ShadowMap> maps);

// add_shadow_map_passes over the runtime's maps.
void add_shadow_map_passes(stages::Device& device, StepList& passes, const stages::SceneBuffers& scene,
                           std::span<ShadowMap> maps);

}  // namespace vplkit
