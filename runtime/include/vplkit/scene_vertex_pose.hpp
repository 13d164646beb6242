#pragma once
// A posable scene's moving vertices as a GPU pass poses them (vplkit/stages/pose_vertices.hpp),
// instead of posing them on the host and uploading them: what is fixed at load (the rest
// vertices in their primitives' object space, joints and weights, morph displacements) and what
// a frame changes (joint and node matrices, morph weights). PosableScene makes both:
//
//   vplkit::scene::PosableScene posable("walk.gltf");
//   if (posable.vertex_pose_refusal().empty()) {
//       vplkit::GpuPose gpu(context, posable.vertex_pose_rest());
//       vplkit::scene::VertexPoseFrame frame;
//       posable.pose_nodes(t, frame);   // lights and cameras posed; vertices left to the GPU
//       gpu.set_frame(frame); record gpu's pass into a step list writing the scene's vertex buffer
//   }

#include "vplkit/shaders/types.hpp"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <vector>

namespace vplkit::scene {

// Fixed at load. Only the instances that can move are here (a node or an ancestor animated, a
// skin's joint or its ancestor animated, or the node's morph weights animated); every other
// vertex keeps its loaded pose.
struct VertexPoseRest {
    std::vector<shaders::PoseRestVertex> vertices;  // instance by instance; `vertex` indexes Scene::vertices
    std::vector<shaders::PoseInstance> instances;
    std::vector<shaders::MorphDelta> deltas;  // empty when no moving instance has targets
    uint32_t matrix_count = 0;                // VertexPoseFrame::matrices.size()
    uint32_t weight_count = 0;                // VertexPoseFrame::morph_weights.size()
};

// One frame's pose of VertexPoseRest's instances.
struct VertexPoseFrame {
    // Per instance from its first_matrix: a skinned one's joints (joint world x inverse bind), a
    // rigid one's node world transform.
    std::vector<glm::mat4> matrices;
    std::vector<float> morph_weights;  // per instance from its first_weight, one per morph target

    bool operator==(const VertexPoseFrame&) const = default;
};

}  // namespace vplkit::scene
