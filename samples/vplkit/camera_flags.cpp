// --position, --target, --up, --fov: one camera for every command that renders a scene's view.

#include "camera_flags.hpp"

#include "cli_checks.hpp"

#include "vplkit/error.hpp"
#include "vplkit/scene_setups.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <optional>
#include <sstream>
#include <string>

namespace vplkit::cli {

namespace {

// "X,Y,Z": three finite numbers, or nothing.
std::optional<glm::vec3> parse_point(const std::string& text) {
    glm::vec3 p(0.0f);
    std::string rest = text;
    for (int i = 0; i < 3; ++i) {
        const size_t comma = rest.find(',');
        const std::string part = i < 2 ? rest.substr(0, comma) : rest;
        size_t used = 0;
        bool ok = (i == 2 || comma != std::string::npos) && !part.empty();
        try {
            if (ok) p[i] = std::stof(part, &used);
        } catch (const std::exception&) {
            ok = false;
        }
        if (!ok || used != part.size() || !std::isfinite(p[i])) return std::nullopt;
        if (i < 2) rest = rest.substr(comma + 1);
    }
    return p;
}

const CLI::Validator kPointCheck(
    [](std::string& text) {
        return parse_point(text) ? std::string() : "expects X,Y,Z (three finite numbers), got '" + text + "'";
    },
    "", "point");

// --NAME X,Y,Z into `into`.
void add_point_option(CLI::App& command, const std::string& name, std::optional<glm::vec3>& into,
                      const std::string& help) {
    command
        .add_option_function<std::string>(
            name, [&into](const std::string& text) { into = parse_point(text); }, help)
        ->check(kPointCheck)
        ->option_text("X,Y,Z");
}

std::string point_text(glm::vec3 p) {
    std::ostringstream s;
    s << p.x << ',' << p.y << ',' << p.z;
    return s.str();
}

}  // namespace

void add_camera_options(CLI::App& command, CameraFlags& flags) {
    add_point_option(command, "--position", flags.position,
                     "a camera at X,Y,Z looking at --target (both needed; they replace the set-up's or the file's "
                     "camera)");
    add_point_option(command, "--target", flags.target, "the point the --position camera looks at");
    add_point_option(command, "--up", flags.up,
                     "with --position and --target: the camera's up direction (default 0,1,0; not along the view)");
    number(command.add_option_function<float>(
               "--fov", [&flags](float degrees) { flags.fov_degrees = degrees; },
               "the vertical field of view in degrees (default: the scene camera's; alone, it turns only the scene "
               "camera's field of view)"),
           "DEG", NumberRange{0.0, 180.0, true, true, "a vertical field of view in degrees, above 0 and below 180"});
}

void check_camera_flags(const CameraFlags& flags) {
    if (flags.position.has_value() != flags.target.has_value()) {
        throw UsageError(
            "--position and --target go together: give both (the camera's place and the point it "
            "looks at)");
    }
    if (flags.up && !flags.position) throw UsageError("--up needs --position and --target");
    if (flags.position) {
        const glm::vec3 view = *flags.target - *flags.position;
        if (!(glm::length(view) > 0.0f)) {
            throw UsageError("--position and --target are the same point (" + point_text(*flags.position) +
                             "): the camera has no view direction");
        }
        const glm::vec3 up = flags.up.value_or(glm::vec3(0.0f, 1.0f, 0.0f));
        const glm::vec3 forward = glm::normalize(view);
        // As scene::look_at decides it: the part of up across the view must not vanish.
        if (!(glm::length(up - forward * glm::dot(forward, up)) > 1e-6f * glm::length(up))) {
            throw UsageError(
                (flags.up ? "--up " + point_text(*flags.up) + " is zero or" : std::string("the default up 0,1,0 is")) +
                " parallel to the view direction from --position to --target; give " +
                (flags.up ? "another --up" : "an --up"));
        }
    }
}

glm::vec3 apply_camera_flags(const CameraFlags& flags, scene::Scene& scene, glm::vec3 target) {
    if (!flags.given()) return target;
    scene::Camera& camera = scene.cameras.at(scene.active_camera);
    if (!flags.position) {
        if (camera.projection != scene::Projection::perspective) {
            throw UsageError(
                "--fov turns a perspective camera's field of view, and the scene's camera is "
                "orthographic; give --position and --target for a perspective one");
        }
        camera.yfov = glm::radians(*flags.fov_degrees);
        return target;
    }
    // The set-up camera's planes, fitted to the scene from the new place (scene_setups.hpp).
    scene::Setup setup;
    setup.name = camera.name;
    setup.width = setup.height = 1;
    setup.camera.position = *flags.position;
    setup.camera.target = *flags.target;
    setup.camera.up = flags.up.value_or(glm::vec3(0.0f, 1.0f, 0.0f));
    const bool perspective = camera.projection == scene::Projection::perspective && camera.yfov > 0.0f;
    setup.camera.yfov_degrees = flags.fov_degrees.value_or(perspective ? glm::degrees(camera.yfov) : 45.0f);
    scene::Camera moved;
    try {
        moved = scene::setup_camera(setup, scene.bounds);
    } catch (const Error& e) {
        throw UsageError(e.what());  // parse_camera_flags checked what look_at refuses; kept as a net
    }
    moved.aspect = camera.aspect;
    moved.origin = camera.origin;
    moved.name = camera.name.empty() ? "command line" : camera.name + " (moved on the command line)";
    camera = moved;
    return *flags.target;
}

}  // namespace vplkit::cli
