#pragma once
// pose_vertices.comp: skinned and morphed vertices posed on the GPU, written into the scene's
// vertex buffer (scene::Vertex layout, 72 bytes) in place of a host pose and its upload. Per frame
// only the matrices and the morph weights change; the rest vertices, instances and morph deltas
// are uploaded once. A foreign renderer fills the buffers from its own skins (the layouts are the
// generated shaders::PoseRestVertex, PoseInstance and MorphDelta):
//
//   rest_vertices[i]  vertex i in its primitive's object space, its instance, the index it is
//                     written at, up to 4 joints (into its instance's matrices) and their weights
//   instances[k]      its vertices' range, its matrices (skinned: one per joint, joint world x
//                     inverse bind; rigid: one, the node's world), its morph targets' deltas and weights
//   matrices          mat4 (column-major, as GLM stores them), this frame's
//   morph_deltas      target t of vertex v of an instance at first_delta + t * vertex_count + v
//   morph_weights     float, this frame's
//
// Only position, normal (unit) and tangent (unit xyz, handedness w; where the instance has
// tangents) of the written vertices change. What reads them next (a raster pass, a BVH refit's
// gather) is ordered after this step by the StepList's barriers.

#include "vplkit/stages/device.hpp"
#include "vplkit/views.hpp"
#include "vplkit/steps.hpp"

#include <cstdint>

namespace vplkit::stages {

struct PoseVerticesBuffers {
    BufferView rest_vertices;   // shaders::PoseRestVertex[vertex_count]
    BufferView instances;       // shaders::PoseInstance[]
    BufferView matrices;        // mat4[]
    BufferView morph_deltas;    // shaders::MorphDelta[] (at least one element: bind any when no target)
    BufferView morph_weights;   // float[] (at least one element)
    BufferView posed_vertices;  // scene::Vertex[]: every rest vertex's `vertex` index inside it
};

// Adds the pass "pose vertices" over `vertex_count` rest vertices. Throws vplkit::Error naming the
// buffer when one is missing or too small for `vertex_count` rest vertices, or larger than
// maxStorageBufferRange (bound whole: such a scene is posed on the host).
void add_pose_vertices_pass(Device& device, StepList& passes, const PoseVerticesBuffers& buffers,
                            uint32_t vertex_count);

}  // namespace vplkit::stages
