#pragma once
// Named standard set-ups (scenes/setups.txt in the repository): a scene, a camera, extra lights
// and a default resolution under one name, so `vplkit render sponza-sun` and the benchmarks mean
// the same picture everywhere. The file format is described at the top of scenes/setups.txt.

#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vplkit::scene {

struct SetupCamera {
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f, 0.0f, -1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yfov_degrees = 45.0f;  // vertical
};

struct Setup {
    std::string name;
    std::string description;
    std::filesystem::path scene;   // absolute, resolved against the set-ups file's folder
    std::string scene_as_written;  // the path as the file gives it
    SetupCamera camera;
    std::vector<Light> lights;  // added to the scene's own (origin LightOrigin::setup)
    uint32_t width = 0;
    uint32_t height = 0;
    std::string where;  // "<set-ups file>:<line>" of the set-up's [name] line, for messages
};

struct Setups {
    std::filesystem::path file;  // absolute
    std::string default_name;
    std::vector<Setup> setups;  // in the file's order

    // Throws vplkit::Error listing the known names when there is no set-up `name`.
    const Setup& find(std::string_view name) const;
    const Setup& default_setup() const { return find(default_name); }
};

// Parses a set-ups file. Throws vplkit::Error "<file>:<line>: <problem>" for a malformed line,
// an unknown or repeated key, a bad number or light, a missing required key, a repeated name, or
// a default that names no set-up. Scene files are not opened here (see require_scene).
Setups load_setups(const std::filesystem::path& file);

// The set-up's scene path, checked to exist: otherwise a vplkit::Error naming the set-up, the
// path as written and as resolved (for the third-party scenes: ../shared/scenes beside the
// repository is missing).
const std::filesystem::path& require_scene(const Setup& setup);

// The set-up's camera, with aspect width / height, and near and far planes from the scene's
// bounds (far: just past the farthest corner; near: 1/1000 of the bounds' diagonal).
Camera setup_camera(const Setup& setup, const Bounds& bounds);

// Loads the set-up's scene (require_scene, then load_gltf), appends the set-up's lights, and
// appends its camera and makes it active, unless options.camera picks one of the file's.
Scene load_setup_scene(const Setup& setup, const LoadOptions& options = {});

}  // namespace vplkit::scene
