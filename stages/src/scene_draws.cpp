#include "scene_draws.hpp"

#include "vplkit/error.hpp"

#include <string>

namespace vplkit::stages {

void check_draw_materials(const SceneBuffers& scene, const char* stage) {
    for (const GpuDraw& draw : scene.draws) {
        if (draw.material >= scene.textures.size()) {
            throw Error(std::string(stage) + ": a draw uses material " + std::to_string(draw.material) +
                        ", but the scene has textures for " + std::to_string(scene.textures.size()));
        }
    }
}

}  // namespace vplkit::stages
