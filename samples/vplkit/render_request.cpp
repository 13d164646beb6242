// The scene a render request names, loaded (a set-up or a file, the extra lights, the camera
// flags), and the sampling options checked before any work.

#include "render_request.hpp"
#include "scene_warnings.hpp"

#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/scene_setups.hpp"

#include <chrono>
#include <optional>
#include <string>

namespace vplkit::cli {

void validate_render_request(const RenderRequest& request) {
    // A sampling option the method refuses (e.g. an interleave that does not divide the block)
    // is a command-line mistake, found before any work.
    try {
        validate_gi_settings(request.settings);
    } catch (const Error& e) {
        throw UsageError(e.what());
    }
}

LoadedScene load_request_scene(RenderRequest& request) {
    const std::optional<uint32_t>& camera = request.camera;
    const std::string& scene_arg = request.scene_arg;
    const std::optional<uint32_t>& width = request.width;
    const std::optional<uint32_t>& height = request.height;
    RenderSettings& settings = request.settings;
    LoadedScene loaded;
    scene::Scene& scene = loaded.scene;
    std::string& described = loaded.described;
    // The scene: a set-up name, or a file.
    const auto load_start = std::chrono::steady_clock::now();
    scene::LoadOptions load_options;
    load_options.camera = camera;
    load_options.time = request.time;
    load_options.animation = request.animation;
    const bool is_file =
        scene_arg.find('/') != std::string::npos || scene_arg.ends_with(".gltf") || scene_arg.ends_with(".glb");
    if (is_file) {
        scene = scene::load_gltf(scene_arg, load_options);
        described = scene_arg;
        loaded.target = scene.bounds.center();
        settings.width = width.value_or(640);
        settings.height = height.value_or(360);
    } else {
        const scene::Setups setups = scene::load_setups(VPLKIT_SETUPS_FILE);
        const scene::Setup& setup = scene_arg.empty() ? setups.default_setup() : setups.find(scene_arg);
        scene = scene::load_setup_scene(setup, load_options);
        described = setup.name + " (" + setup.scene.string() + ")";
        loaded.target = setup.camera.target;
        settings.width = width.value_or(setup.width ? setup.width : 640);
        settings.height = height.value_or(setup.height ? setup.height : 360);
    }
    scene.lights.insert(scene.lights.end(), request.extra_lights.begin(), request.extra_lights.end());
    loaded.target = apply_camera_flags(request.camera_flags, scene, loaded.target);
    report_scene_warnings(scene, request.strict);
    if (request.lambertian) scene::use_lambertian_materials(scene);
    loaded.load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start).count();
    return loaded;
}

}  // namespace vplkit::cli
