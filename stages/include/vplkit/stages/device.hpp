#pragma once
// stages::Device: what a stage needs of the caller's device. The VkDevice the stage's
// pipelines are created on (once, on first use, kept until the Device is destroyed or
// destroy_pipelines() is called), an optional VkPipelineCache, and the few limits the stages
// check their sizes against. It owns no Vulkan object except those pipelines.
//
//   vplkit::stages::Device kit(physical_device, device);   // queries the limits
//   vplkit::StepList steps;
//   vplkit::stages::add_sst_passes(kit, steps, leaves, nodes, counters, count);
//   steps.record(cmd);
//
// The device must have been created with what required_device_features() lists (Vulkan 1.3,
// VK_KHR_push_descriptor, shaderInt64, scalarBlockLayout, bufferDeviceAddress, synchronization2,
// dynamicRendering; vplkit/stages/device_requirements.hpp), and missing_device_features() says what a device lacks.

#include "vplkit/error.hpp"
#include "vplkit/views.hpp"

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <typeindex>
#include <typeinfo>
#include <utility>

namespace vplkit::stages {

// The device limits a stage validates against (from VkPhysicalDeviceLimits).
struct Limits {
    uint64_t max_storage_buffer_range = 0;
    uint64_t min_storage_buffer_offset_alignment = 0;
    uint32_t max_shared_memory_bytes = 0;
    std::array<uint32_t, 3> max_workgroup_size{};
    uint32_t max_workgroup_invocations = 0;
    std::array<uint32_t, 3> max_workgroup_count{};
    // A CPU implementation (lavapipe): some stages pick other defaults there (measured).
    bool cpu = false;

    static Limits query(VkPhysicalDevice physical_device);
};

// Scratch memory a stage object keeps for its lifetime (a sort's ping-pong copy of the pairs):
// the view, and whatever keeps the memory alive (released with the last copy).
struct ScratchBuffer {
    BufferView view;
    std::shared_ptr<void> owner;
};

class Device {
public:
    Device() = default;
    Device(VkDevice device, const Limits& limits, VkPipelineCache cache = VK_NULL_HANDLE) {
        attach(device, limits, cache);
    }
    Device(VkPhysicalDevice physical_device, VkDevice device, VkPipelineCache cache = VK_NULL_HANDLE)
        : Device(device, Limits::query(physical_device), cache) {}
    virtual ~Device() { destroy_pipelines(); }
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    VkDevice device() const { return device_; }
    const Limits& limits() const { return limits_; }

    // The pipeline of a generated shader type P (e.g. vplkit::shaders::morton_keys::Pipeline)
    // for specialization `spec`, created on first use through P::create(device, cache, spec, &p)
    // and kept. One pipeline per (P, spec bytes). Throws Error naming P when creation fails.
    template <class P>
    const P& pipeline(const typename P::Spec& spec = {});

    // Destroys every pipeline created so far (before the VkDevice goes).
    void destroy_pipelines();

    // Device-local storage memory for stage objects that need scratch space and were not given
    // buffers of their own (RadixSorter). This base class has no allocator and throws Error
    // naming the size: pass the buffers explicitly, or override this with your allocator
    // (vplkit::Context does).
    virtual ScratchBuffer create_scratch_buffer(VkDeviceSize bytes, const std::string& name);

protected:
    void attach(VkDevice device, const Limits& limits, VkPipelineCache cache);

private:
    void* cached_pipeline(std::type_index type, std::string key, const std::function<VkResult(void** out)>& create,
                          void (*destroy)(void*));

    VkDevice device_ = VK_NULL_HANDLE;
    VkPipelineCache cache_ = VK_NULL_HANDLE;
    Limits limits_;
    struct PipelineEntry {
        void* pipeline = nullptr;
        void (*destroy)(void*) = nullptr;
    };
    std::mutex mutex_;
    std::map<std::pair<std::type_index, std::string>, PipelineEntry> pipelines_;
};

template <class P>
const P& Device::pipeline(const typename P::Spec& spec) {
    using Spec = typename P::Spec;
    static_assert(std::is_trivially_copyable_v<Spec> && std::is_standard_layout_v<Spec>,
                  "a generated Spec's bytes are its specialization data");
    // An empty Spec still has sizeof 1 with an indeterminate byte: it must not become the key.
    std::string key;
    if constexpr (!std::is_empty_v<Spec>) {
        key.resize(sizeof(Spec));
        std::memcpy(key.data(), &spec, sizeof(Spec));
    }
    void* p = cached_pipeline(
        std::type_index(typeid(P)), std::move(key),
        [&](void** out) -> VkResult {
            auto* created = new P();
            const VkResult result = P::create(device_, cache_, spec, created);
            if (result == VK_SUCCESS) {
                *out = created;
            } else {
                delete created;
            }
            return result;
        },
        [](void* owned) {
            auto* typed = static_cast<P*>(owned);
            typed->destroy();
            delete typed;
        });
    return *static_cast<const P*>(p);
}

}  // namespace vplkit::stages
