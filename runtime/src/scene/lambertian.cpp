#include "vplkit/scene.hpp"

namespace vplkit::scene {

void use_lambertian_materials(Scene& scene) {
    for (Material& m : scene.materials) {
        m.metallic_factor = 0.0f;
        m.roughness_factor = kLambertianRoughness;  // with no texture, the G-buffer holds it exactly
        m.metallic_roughness_texture = kNoTexture;
    }
}

}  // namespace vplkit::scene
