#pragma once
// A small animated glTF for the pose tests: a grey floor (4 x 4, z = 0), a grey block quad above
// it (0.5 x 0.5 at z = 0.6) and a point light at z = 2. Animation 0 "slide" moves the block along
// x from -0.75 to 0.25 over t in [0, 2]; animation 1 "swing" the light from x = -0.5 to 0.5.

#include "animation_files.hpp"

#include <vplkit/scene.hpp>

#include <filesystem>

namespace pose_test {

// Writes the file into `dir`; returns its path.
std::filesystem::path write_moving_scene(const std::filesystem::path& dir);

// The camera the tests look at it with (above, in front, z up).
vplkit::scene::Camera moving_scene_camera();

}  // namespace pose_test
