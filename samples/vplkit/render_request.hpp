#pragma once
// What `vplkit render` and `vplkit sequence` read alike: the device, the scene (a standard set-up
// or a file, extra lights, the BRDF), the size and every indirect-light option, parsed into
// RenderSettings; then the scene loaded for them. The outputs are each command's own.

#include "camera_flags.hpp"
#include "cli.hpp"

#include "vplkit/context.hpp"
#include "vplkit/render_settings.hpp"
#include "vplkit/scene.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vplkit::cli {

struct RenderRequest {
    ContextOptions context;
    bool strict = false;    // --strict: a scene warning fails the run
    std::string scene_arg;  // --scene: a set-up name or a file ("" = the default set-up)
    std::optional<uint32_t> width, height, camera;
    std::optional<double> time;              // --time: the file's animations posed at T seconds
    std::optional<std::string> animation;    // --animation: only this one (name or index)
    CameraFlags camera_flags;                // --position, --target, --up, --fov
    std::vector<scene::Light> extra_lights;  // --sun, --point
    RenderSettings settings;
    bool lambertian = false;     // --brdf lambert
    bool denoise_given = false;  // --denoise was on the command line (sequence's default differs)
};

// Reads render's options except the outputs and --frames (UsageError for a mistake).
RenderRequest parse_render_request(Args& args);
// The sampling options checked before any work (a refused one is a UsageError).
void validate_render_request(const RenderRequest& request);

struct LoadedScene {
    scene::Scene scene;  // with the set-up's and the extra lights, its camera active
    std::string described;
    // The point the camera looks at: --target, the set-up's target, or the centre of a file's bounds.
    glm::vec3 target{0.0f};
    double load_ms = 0.0;
};
// Loads the request's scene and sets its default size into request.settings (unless given).
LoadedScene load_request_scene(RenderRequest& request);

}  // namespace vplkit::cli
