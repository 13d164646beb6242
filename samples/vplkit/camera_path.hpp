#pragma once
// Camera paths for `vplkit sequence`: an orbit about a target, or keyframes from a file.
//
// Keyframe file: one key per line, "TIME PX PY PZ TX TY TZ" (seconds, position, target; spaces
// or commas), times strictly increasing, at least two keys; '#' starts a comment. Frame i of n
// sits at time t0 + (t1 - t0) i / (n - 1), position and target interpolated linearly between the
// keys around it.

#include "vplkit/scene.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace vplkit::cli {

struct CameraKey {
    double time = 0.0;
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f};
};

// Throws vplkit::Error "<file>:<line>: <problem>" for a malformed line, too few keys or times
// that do not increase.
std::vector<CameraKey> read_camera_keys(const std::filesystem::path& file);

// n cameras along the keys (see above), each with `base`'s field of view, planes and aspect, +Y up.
std::vector<scene::Camera> keyframe_path(const std::vector<CameraKey>& keys, const scene::Camera& base, uint32_t n);

// n cameras turning `degrees` in all about the axis `up` (default +Y, the vertical) through
// `target`, starting at `base` (frame 0 is `base`'s position, looking at the target), `up` up.
std::vector<scene::Camera> orbit_path(const scene::Camera& base, glm::vec3 target, float degrees, uint32_t n,
                                      glm::vec3 up = {0.0f, 1.0f, 0.0f});

}  // namespace vplkit::cli
