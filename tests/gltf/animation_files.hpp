#pragma once
// Small animated glTF files for the animation tests (glTF 2.0 3.11): animations stated as keys
// and values in the test, written one sampler per channel, outputs as floats or normalized
// integers. The expectations are computed in the tests, beside each use.

#include "gltf_builder.hpp"

#include <string>
#include <vector>

namespace gltf_features {

using scene_test::GltfBuilder;

// One channel: `values` flat, per key the path's components (3 translation/scale, 4 rotation
// (x, y, z, w), the morph target count for weights), CUBICSPLINE per key in-tangent, value,
// out-tangent. Outputs as `component_type` (kFloat, else that integer type normalized).
struct ChannelKeys {
    int node = 0;
    std::string path = "translation";
    std::string interpolation = "LINEAR";
    std::vector<float> times;
    std::vector<float> values;
    int component_type = scene_test::kFloat;
};

struct AnimationKeys {
    std::string name;
    std::vector<ChannelKeys> channels;
};

// Appends `animations` to `b`'s top-level JSON (after anything already there).
void add_animations(GltfBuilder& b, const std::vector<AnimationKeys>& animations);

// The unit quad (corners (0,0,0), (1,0,0), (1,1,0), (0,1,0)) on node 0 at the origin, a point
// light on node 1 at (0.5, 0.5, 1), and `animations`.
GltfBuilder animated_quad(const std::vector<AnimationKeys>& animations);

// For the command-line tests: animated_quad with animation 0 "slide" moving the quad from x = 0
// at t = 0 to x = 1 at t = 2 (LINEAR) and animation 1 "swing" moving the light from x = 0.5 to
// x = 1.5 over the same time.
GltfBuilder animated_scene();

}  // namespace gltf_features
