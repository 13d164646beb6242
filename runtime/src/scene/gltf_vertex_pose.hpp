#pragma once
// The moving instances of a loaded scene laid out for the GPU pose (vplkit/scene_vertex_pose.hpp),
// and each frame's matrices and morph weights read from the posed nodes, by the same functions the
// host pose uses (joint_matrices, NodeWorlds, morph_weights).

#include "scene/gltf_instances.hpp"
#include "vplkit/scene_vertex_pose.hpp"

#include <string>
#include <vector>

namespace vplkit::scene::detail {

// Where one moving instance's matrices and weights come from each frame.
struct VertexPoseSource {
    int node = 0;
    int skin = -1;  // -1: rigid, posed by the node's world transform
    int mesh = 0;
    uint32_t target_count = 0;
};

struct VertexPoseSetup {
    VertexPoseRest rest;
    std::vector<VertexPoseSource> sources;  // one per rest.instances entry
    std::string refusal;                    // empty: the GPU can pose every moving vertex
};

// The moving instances of `scene` (loaded from `source`'s model by append_node_instances, whose
// decoded primitives are `decoded`). An instance the GPU pass cannot pose as the host does
// (generated flat normals or tangents: they depend on the posed triangles; more than four joint
// influences; vertices the loader dropped) makes `refusal` a line naming it.
VertexPoseSetup vertex_pose_setup(const GltfSource& source, const DecodedMeshes& decoded, const Scene& scene);

// This frame's matrices and weights of `setup`'s instances, from the model as posed now.
// Fails naming the node where a morph weight count does not match its targets.
VertexPoseFrame vertex_pose_frame(const GltfSource& source, const VertexPoseSetup& setup);

}  // namespace vplkit::scene::detail
