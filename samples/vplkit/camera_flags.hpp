#pragma once
// The camera on the command line, shared by render, plan, bench gi, bench direct and sequence:
// --position X,Y,Z --target X,Y,Z [--up X,Y,Z] [--fov DEG]. Parsed and checked once here; the
// scene's active camera is then replaced by the one they describe.

#include "cli.hpp"

#include <CLI/CLI.hpp>

#include "vplkit/scene.hpp"

#include <glm/vec3.hpp>

#include <optional>

namespace vplkit::cli {

struct CameraFlags {
    std::optional<glm::vec3> position, target, up;
    std::optional<float> fov_degrees;  // vertical, in (0, 180)

    bool given() const { return position || target || up || fov_degrees; }
};

// Declares the four options on `command`, read into `flags`; each value is checked as it is parsed
// (three finite numbers; a field of view in (0, 180) degrees).
void add_camera_options(CLI::App& command, CameraFlags& flags);
// After parsing, what the options say together: a UsageError for --position without --target (or
// the reverse), --up without them, the same point as position and target, or an up parallel to the
// view direction.
void check_camera_flags(const CameraFlags& flags);

// Makes the flags' camera the scene's active one (the set-up's or file's is the default of what
// is not given: --fov alone keeps its place and turns only the field of view) and returns the
// point it looks at (`target` when the flags name none). The near and far planes are fitted to
// the scene's bounds from the new position. A UsageError for --fov alone on an orthographic camera.
glm::vec3 apply_camera_flags(const CameraFlags& flags, scene::Scene& scene, glm::vec3 target);

}  // namespace vplkit::cli
