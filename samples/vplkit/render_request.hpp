#pragma once
// What `vplkit render`, `plan`, `sequence` and `view` read alike: the device, the scene (a standard set-up
// or a file, extra lights, the BRDF), the size and every indirect-light option, parsed into
// RenderSettings; then the scene loaded for them. The outputs are each command's own.

#include "camera_flags.hpp"
#include "cli.hpp"

#include <CLI/CLI.hpp>

#include "vplkit/context.hpp"
#include "vplkit/render_settings.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_pose.hpp"

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

// Render's options except the outputs and --frames, declared on a command (each with its help and
// its check: render_options.cpp); after parsing, request() reads them and checks what they say
// together (UsageError for a combination refused, e.g. --spp with a method that takes none).
class RenderOptions {
public:
    explicit RenderOptions(CLI::App& command);
    RenderOptions(const RenderOptions&) = delete;
    RenderOptions& operator=(const RenderOptions&) = delete;

    RenderRequest request() const;

private:
    bool given(const std::string& option) const;

    const CLI::App& command_;
    RenderRequest request_;  // the options bound to a field of their own
    std::string method_ = "direct", direct_ = "auto", traversal_ = "substitute", glossy_lobe_ = "auto";
    std::string gi_resolution_ = "full", denoise_ = "off", vpl_source_ = "auto", brdf_ = "gltf";
    std::string exposure_ = "auto";
    std::vector<std::string> suns_, points_;
    bool no_reuse_ = false;
};

// --sun and --point (repeatable), each value checked by the scene loader's parse as it is read.
void add_light_options(CLI::App& command, std::vector<std::string>& suns, std::vector<std::string>& points);

// The sampling options checked before any work (a refused one is a UsageError).
void validate_render_request(const RenderRequest& request);

// For the commands that show frame after frame (sequence, view), which the filter is for: svgf
// for a sampled method unless --denoise was given (never for exact or direct light alone).
void filter_frames_by_default(RenderRequest& request);

struct LoadedScene {
    scene::Scene scene;  // with the set-up's and the extra lights, its camera active
    // Instead of `scene` when loaded posable (load_request_posable): a glTF file posed again
    // per frame without reading it (its scene() is the one to render).
    std::unique_ptr<scene::PosableScene> posable;
    scene::Scene& active() { return posable ? posable->scene() : scene; }
    std::string described;
    // The point the camera looks at: --target, the set-up's target, or the centre of a file's bounds.
    glm::vec3 target{0.0f};
    double load_ms = 0.0;
};
// Loads the request's scene and sets its default size into request.settings (unless given).
LoadedScene load_request_scene(RenderRequest& request);
// The same for a glTF file kept posable (scene::PosableScene), posed at request.time or 0.
// UsageError for a set-up name: a set-up's scene is not posed.
LoadedScene load_request_posable(RenderRequest& request);

}  // namespace vplkit::cli
