#pragma once
// An animated glTF file whose vertices the GPU pose must get right in every branch, at any size:
// a tube skinned to a chain of three joints (weights that sum to 1.02, rescaled by the pose; a
// third influence in every vertex) with a morph target (position, normal and tangent
// displacements) and tangents whose handedness alternates ring by ring, and a mirrored quad
// (scale -1 in x) with tangents on a node that turns and slides. Animation "bend" (0 to 2 s)
// turns joints 1 and 2, slides joint 0, sets the morph weight and moves the quad. A point light
// at (0, 1, 2) lights it for a renderer.

#include "gltf_builder.hpp"

#include <cstdint>

namespace gltf_features {

// The tube has `rings` rings of `sides` + 1 vertices (the seam doubled): rings x (sides + 1)
// vertices in all, plus the quad's 4. rings >= 2, sides >= 3.
scene_test::GltfBuilder skinned_tube(uint32_t rings, uint32_t sides);

}  // namespace gltf_features
