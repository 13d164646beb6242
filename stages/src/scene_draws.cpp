#include "scene_draws.hpp"

#include "vplkit/error.hpp"

#include <string>

namespace vplkit::stages {

void check_draw_materials(const SceneBuffers& scene, const char* stage) {
    for (const GpuDraw& draw : scene.draws) {
        if (draw.material >= scene.textures.size()) {
            throw Error(std::string(stage) + ": a draw uses material " + std::to_string(draw.material) +
                        ", but the scene has textures for " + std::to_string(scene.textures.size()));
        }
    }
}

void check_scene_range(const SceneBuffers& scene, uint64_t max_storage_buffer_range, const char* stage) {
    if (scene.addressed) return;
    for (const BufferView* view : {&scene.vertices, &scene.indices, &scene.previous_vertices}) {
        if (view->size > max_storage_buffer_range) {
            throw Error(std::string(stage) + ": the scene's buffer '" + view->name + "' (" +
                        std::to_string(view->size) +
                        " bytes) is larger than a storage binding may be on this device (" + "maxStorageBufferRange " +
                        std::to_string(max_storage_buffer_range) +
                        "): read it at its device address (SceneBuffers::addressed)");
        }
    }
}

VkDeviceAddress view_address(VkDevice device, const BufferView& view) {
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = view.buffer;
    return vkGetBufferDeviceAddress(device, &info) + view.offset;
}

}  // namespace vplkit::stages
