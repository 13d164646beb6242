#include "vplkit/stages/device.hpp"

#include <cxxabi.h>

#include <cstdlib>

namespace vplkit::stages {
namespace {

std::string demangle(const char* name) {
    int status = 0;
    char* text = abi::__cxa_demangle(name, nullptr, nullptr, &status);
    std::string out = (status == 0 && text) ? text : name;
    std::free(text);
    return out;
}

}  // namespace

Limits Limits::query(VkPhysicalDevice physical_device) {
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(physical_device, &properties);
    const VkPhysicalDeviceLimits& l = properties.limits;
    Limits limits;
    limits.max_storage_buffer_range = l.maxStorageBufferRange;
    limits.min_storage_buffer_offset_alignment = l.minStorageBufferOffsetAlignment;
    limits.max_shared_memory_bytes = l.maxComputeSharedMemorySize;
    limits.max_workgroup_invocations = l.maxComputeWorkGroupInvocations;
    for (int i = 0; i < 3; ++i) {
        limits.max_workgroup_size[i] = l.maxComputeWorkGroupSize[i];
        limits.max_workgroup_count[i] = l.maxComputeWorkGroupCount[i];
    }
    limits.cpu = properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    return limits;
}

void Device::attach(VkDevice device, const Limits& limits, VkPipelineCache cache) {
    destroy_pipelines();
    device_ = device;
    limits_ = limits;
    cache_ = cache;
}

void Device::destroy_pipelines() {
    std::lock_guard lock(mutex_);
    for (auto& [key, entry] : pipelines_) entry.destroy(entry.pipeline);
    pipelines_.clear();
}

ScratchBuffer Device::create_scratch_buffer(VkDeviceSize bytes, const std::string& name) {
    throw Error("vplkit: '" + name + "' needs " + std::to_string(bytes) +
                " bytes of scratch memory, and this stages::Device has no allocator: pass the buffers to the stage "
                "or override Device::create_scratch_buffer");
}

void* Device::cached_pipeline(std::type_index type, std::string key, const std::function<VkResult(void**)>& create,
                              void (*destroy)(void*)) {
    std::lock_guard lock(mutex_);
    if (device_ == VK_NULL_HANDLE) throw Error("vplkit: a stages::Device with no VkDevice cannot create pipelines");
    auto found = pipelines_.find({type, key});
    if (found != pipelines_.end()) return found->second.pipeline;
    void* pipeline = nullptr;
    const VkResult result = create(&pipeline);
    if (result != VK_SUCCESS) {
        throw Error("vplkit: creating the pipeline " + demangle(type.name()) + " failed: " + result_name(result),
                    result);
    }
    pipelines_.emplace(std::make_pair(type, std::move(key)), PipelineEntry{pipeline, destroy});
    return pipeline;
}

}  // namespace vplkit::stages
