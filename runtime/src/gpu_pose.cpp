// GpuPose: the rest data uploaded once, the frame's matrices and weights written each frame.

#include "vplkit/gpu_pose.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/stages/pose_vertices.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace vplkit {

namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

// A buffer holding `values` (at least one element: Vulkan has no empty buffers).
template <class T>
Buffer upload_array(Context& context, const std::vector<T>& values, MemoryUse memory, const char* name) {
    Buffer buffer = Buffer::create(context, std::max<size_t>(values.size(), 1) * sizeof(T), kStorage, memory, name);
    if (!values.empty()) buffer.upload(values);
    return buffer;
}

}  // namespace

GpuPose::GpuPose(Context& context, const scene::VertexPoseRest& rest)
    : context_(&context),
      vertex_count_(uint32_t(rest.vertices.size())),
      matrix_count_(rest.matrix_count),
      weight_count_(rest.weight_count) {
    if (vertex_count_ == 0) return;
    for (const shaders::PoseRestVertex& v : rest.vertices) last_vertex_ = std::max(last_vertex_, v.vertex);
    rest_ = upload_array(context, rest.vertices, MemoryUse::device, "pose rest vertices");
    instances_ = upload_array(context, rest.instances, MemoryUse::device, "pose instances");
    deltas_ = upload_array(context, rest.deltas, MemoryUse::device, "morph deltas");
    matrices_ = upload_array(context, std::vector<glm::mat4>(matrix_count_, glm::mat4(1.0f)), MemoryUse::upload,
                             "pose matrices");
    weights_ = upload_array(context, std::vector<float>(weight_count_, 0.0f), MemoryUse::upload, "morph weights");
}

void GpuPose::set_frame(const scene::VertexPoseFrame& frame) {
    if (frame.matrices.size() != matrix_count_ || frame.morph_weights.size() != weight_count_) {
        throw Error("GPU pose: a frame of " + std::to_string(frame.matrices.size()) + " matrices and " +
                    std::to_string(frame.morph_weights.size()) + " morph weights, the rest pose has " +
                    std::to_string(matrix_count_) + " and " + std::to_string(weight_count_));
    }
    if (vertex_count_ == 0) return;
    if (!frame.matrices.empty()) matrices_.upload(frame.matrices);
    if (!frame.morph_weights.empty()) weights_.upload(frame.morph_weights);
}

void GpuPose::add_pose_pass(StepList& passes, const BufferView& vertices) const {
    if (vertex_count_ == 0) return;
    const VkDeviceSize vertex_bytes = sizeof(shaders::SceneVertex);
    if (vertices.size < (VkDeviceSize(last_vertex_) + 1) * vertex_bytes) {
        throw Error("GPU pose: '" + vertices.name + "' holds " + std::to_string(vertices.size / vertex_bytes) +
                    " vertices, the pose writes vertex " + std::to_string(last_vertex_));
    }
    stages::add_pose_vertices_pass(*context_, passes, {rest_, instances_, matrices_, deltas_, weights_, vertices},
                                   vertex_count_);
}

}  // namespace vplkit
