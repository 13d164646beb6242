#pragma once
// The light tree over a scene's own lights (stages/scene_light_tree.hpp), as the runtime keeps
// it: the proxies made from the scene on the host, the buffers, the sorter, and the passes that
// build it. The lights never change within a Renderer, so it is built once.

#include "vplkit/buffer.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/scene_light_tree.hpp"
#include "vplkit/stages/sort.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace vplkit {
class Context;
class PassList;
}  // namespace vplkit

namespace vplkit {

// What the tree holds, made on the host: a proxy (position, normal, RGB power as flux) per
// light, emissive triangles first (upload_emitters' order), then the scene's point and spot
// lights (directional ones have no position: direct_light.comp keeps them).
struct LightTreeLights {
    std::vector<shaders::Vpl> proxies;
    uint32_t triangle_count = 0;
    std::vector<scene::Light> punctual;  // the point and spot lights, in scene order
};
LightTreeLights light_tree_lights(const scene::Scene& scene);

// The scene's directional lights alone (what direct light adds besides the tree).
std::vector<scene::Light> directional_lights(const scene::Scene& scene);

class GpuLightTree {
public:
    // Allocates and uploads; `emitters` (upload_emitters of the same scene) must outlive the
    // tree. Throws vplkit::Error when the scene has no emissive triangle, point or spot light.
    static GpuLightTree create(Context& context, const scene::Scene& scene, const GpuEmitters& emitters);

    // Adds the build passes (stages::add_scene_light_tree_passes).
    void add_build_passes(Context& context, PassList& passes);

    uint32_t count() const { return count_; }
    uint32_t triangle_count() const { return triangle_count_; }
    // The tree as the sampling stage reads it (valid after the build passes ran).
    stages::SceneLightTreeBuffers buffers() const;
    // The built tree's buffers, for reading back (tests): LightTreeNode[], uint32 leaf -> light.
    const Buffer& nodes() const;
    const Buffer& leaf_lights() const;

private:
    struct State;
    std::shared_ptr<State> state_;  // shared: a tree is handed around by value
    uint32_t count_ = 0;
    uint32_t triangle_count_ = 0;
};

}  // namespace vplkit
