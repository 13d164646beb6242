#include "vplkit/stages/pose_vertices.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/pose_vertices.hpp"
#include "vplkit/stages/binding_uses.hpp"

#include <string>

namespace vplkit::stages {

namespace {

void require(const BufferView& view, VkDeviceSize bytes, const std::string& what) {
    if (!view) throw Error("pose vertices: no '" + what + "' buffer");
    if (view.size < bytes) {
        throw Error("pose vertices: '" + (view.name.empty() ? what : view.name) + "' holds " +
                    std::to_string(view.size) + " bytes, " + std::to_string(bytes) + " needed");
    }
}

// Every buffer is bound whole; past maxStorageBufferRange a binding would be invalid (VUID-00333).
// The scene's vertices (72 bytes each) pass it first, at 1.86M vertices on lavapipe.
void require_bindable(const BufferView& view, uint64_t max_storage_buffer_range, const std::string& what) {
    if (view.size > max_storage_buffer_range) {
        throw Error("pose vertices: '" + (view.name.empty() ? what : view.name) + "' (" + std::to_string(view.size) +
                    " bytes) is larger than a storage binding may be on this device (maxStorageBufferRange " +
                    std::to_string(max_storage_buffer_range) + "): pose this scene on the host");
    }
}

}  // namespace

void add_pose_vertices_pass(Device& device, StepList& passes, const PoseVerticesBuffers& buffers,
                            uint32_t vertex_count) {
    if (vertex_count == 0) return;
    require(buffers.rest_vertices, VkDeviceSize(vertex_count) * sizeof(shaders::PoseRestVertex), "rest vertices");
    require(buffers.instances, sizeof(shaders::PoseInstance), "instances");
    require(buffers.matrices, 64, "matrices");
    require(buffers.morph_deltas, sizeof(shaders::MorphDelta), "morph deltas");
    require(buffers.morph_weights, sizeof(float), "morph weights");
    require(buffers.posed_vertices, sizeof(shaders::SceneVertex), "posed vertices");
    const uint64_t range = device.limits().max_storage_buffer_range;
    require_bindable(buffers.rest_vertices, range, "rest vertices");
    require_bindable(buffers.instances, range, "instances");
    require_bindable(buffers.matrices, range, "matrices");
    require_bindable(buffers.morph_deltas, range, "morph deltas");
    require_bindable(buffers.morph_weights, range, "morph weights");
    require_bindable(buffers.posed_vertices, range, "posed vertices");
    passes.names({buffers.rest_vertices, buffers.instances, buffers.matrices, buffers.morph_deltas,
                  buffers.morph_weights, buffers.posed_vertices});

    shaders::pose_vertices::Bindings b;
    b.rest_vertices = buffers.rest_vertices.descriptor();
    b.pose_instances = buffers.instances.descriptor();
    b.pose_matrices = buffers.matrices.descriptor();
    b.morph_deltas = buffers.morph_deltas.descriptor();
    b.morph_weights = buffers.morph_weights.descriptor();
    b.posed_vertices = buffers.posed_vertices.descriptor();
    shaders::pose_vertices::Push push{};
    push.vertex_count = vertex_count;
    add_dispatch<shaders::pose_vertices::Module>(
        passes, "pose vertices", device.pipeline<shaders::pose_vertices::Pipeline>(), b, push, vertex_count);
}

}  // namespace vplkit::stages
