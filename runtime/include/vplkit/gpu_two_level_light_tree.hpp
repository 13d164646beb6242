#pragma once
// The two-level light tree over a scene's own lights (two_level_light_tree.hpp: a bottom tree per
// mesh light, a top tree over them), built on the host and uploaded once: the lights never change
// within a Renderer, and the kit has no moving instances, so neither level is ever rebuilt.

#include "vplkit/buffer.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/direct_light_tree.hpp"

#include <cstdint>
#include <memory>

namespace vplkit {
class Context;
}

namespace vplkit {

class GpuTwoLevelLightTree {
public:
    // Builds (build_two_level_light_tree over two_level_lights) and uploads; `emitters`
    // (upload_emitters of the same scene) must outlive the tree. Throws vplkit::Error when the
    // scene has no emissive triangle, point or spot light.
    static GpuTwoLevelLightTree create(Context& context, const scene::Scene& scene, const GpuEmitters& emitters);

    uint32_t count() const { return count_; }              // lights
    uint32_t mesh_lights() const { return mesh_lights_; }  // bottom trees
    stages::TwoLevelLightTreeBuffers buffers() const;

private:
    struct State;
    std::shared_ptr<State> state_;  // shared: a tree is handed around by value
    uint32_t count_ = 0;
    uint32_t mesh_lights_ = 0;
};

}  // namespace vplkit
