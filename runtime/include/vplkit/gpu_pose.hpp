#pragma once
// A posable scene's moving vertices posed on the GPU (stages/pose_vertices.hpp) over buffers
// uploaded once: per frame only the joint and node matrices and the morph weights are written
// (host-visible memory, no staging copy), and one pass writes the posed vertices into the
// scene's vertex buffer. The host pose (PosableScene::pose) stays the reference it is tested against.
//
//   vplkit::GpuPose gpu(context, posable.vertex_pose_rest());
//   vplkit::scene::VertexPoseFrame frame;
//   posable.pose_nodes(t, frame);
//   gpu.set_frame(frame);
//   gpu.add_pose_pass(passes, gpu_scene.vertices());  // before what reads the vertices

#include "vplkit/buffer.hpp"
#include "vplkit/scene_vertex_pose.hpp"
#include "vplkit/steps.hpp"

#include <cstdint>

namespace vplkit {

class Context;

class GpuPose {
public:
    // Uploads `rest` (blocking). A rest without vertices poses nothing (add_pose_pass adds no step).
    GpuPose(Context& context, const scene::VertexPoseRest& rest);

    // This frame's matrices and weights, written into the buffers the pass reads: call it when no
    // pass of this object is in flight (every runtime submission waits for its work). Throws Error
    // for a frame whose counts are not the rest's.
    void set_frame(const scene::VertexPoseFrame& frame);

    // Adds "pose vertices", writing `vertices` (scene::Vertex[], e.g. GpuScene::vertices()) at the
    // rest vertices' indices. Throws Error when they lie outside `vertices`.
    void add_pose_pass(StepList& passes, const BufferView& vertices) const;

    uint32_t vertex_count() const { return vertex_count_; }

private:
    Context* context_ = nullptr;
    uint32_t vertex_count_ = 0;
    uint32_t last_vertex_ = 0;  // the largest index a rest vertex writes
    uint32_t matrix_count_ = 0;
    uint32_t weight_count_ = 0;
    Buffer rest_, instances_, deltas_, matrices_, weights_;
};

}  // namespace vplkit
