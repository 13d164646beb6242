#pragma once
// What vplkit knows about a Vulkan device: identity, the limits stages size themselves by, and
// which required and optional features it has. Filled once per device at enumeration.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vplkit {

enum class DeviceType { discrete_gpu, integrated_gpu, virtual_gpu, cpu, other };

// "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other".
const char* device_type_name(DeviceType type);

struct DeviceFeatures {
    // Required: a device without any of these cannot run vplkit (DeviceInfo::missing names them).
    bool vulkan_1_3 = false;
    bool synchronization2 = false;
    bool push_descriptor = false;      // VK_KHR_push_descriptor: generated dispatch() pushes its bindings
    bool shader_int64 = false;         // 64-bit sort keys
    bool scalar_block_layout = false;  // vec3 arrays without padding in shared structs
    bool timestamps = false;           // on the graphics+compute queue vplkit uses

    // Optional: enabled when present; a stage that needs one checks it and says so.
    bool shader_float64 = false;  // GPU ground truth in double
    bool shader_buffer_int64_atomics = false;
    bool shader_buffer_float32_atomic_add = false;  // VK_EXT_shader_atomic_float
    bool shader_shared_float32_atomic_add = false;
    bool subgroup_size_control = false;  // pin/require full subgroups in compute
    bool compute_full_subgroups = false;
    bool subgroup_basic = false;  // subgroup ops available in compute shaders
    bool subgroup_vote = false;
    bool subgroup_arithmetic = false;
    bool subgroup_ballot = false;
    bool subgroup_shuffle = false;
    bool subgroup_shuffle_relative = false;
    bool subgroup_clustered = false;
    bool subgroup_quad = false;

    // Reported only (never enabled by the runtime): the optional hardware ray-tracing path.
    bool ray_tracing_pipeline = false;    // VK_KHR_ray_tracing_pipeline
    bool acceleration_structure = false;  // VK_KHR_acceleration_structure
    bool ray_query = false;               // VK_KHR_ray_query
};

struct DeviceInfo {
    uint32_t index = 0;  // position in vkEnumeratePhysicalDevices
    std::string name;
    DeviceType type = DeviceType::other;
    std::string type_name;    // device_type_name(type)
    std::string driver_name;  // "llvmpipe", "NVIDIA"
    std::string driver_info;  // "Mesa 22.3.6 (LLVM 15.0.6)", driver version text
    uint32_t vendor_id = 0;
    uint32_t device_id = 0;
    uint32_t api_version = 0;        // VK_MAKE_API_VERSION as the device reports it
    std::string api_version_string;  // "1.3.230"

    // Never assume a subgroup size: lavapipe has 8, NVIDIA 32, AMD 32 or 64.
    uint32_t subgroup_size = 0;
    uint32_t min_subgroup_size = 0;
    uint32_t max_subgroup_size = 0;
    VkSubgroupFeatureFlags subgroup_operations = 0;
    VkShaderStageFlags subgroup_stages = 0;

    float timestamp_period_ns = 0.0f;    // nanoseconds per timestamp tick
    uint32_t timestamp_valid_bits = 0;   // on the chosen queue family
    uint32_t queue_family = UINT32_MAX;  // graphics+compute family vplkit would use

    uint32_t max_shared_memory_bytes = 0;
    std::array<uint32_t, 3> max_workgroup_size{};
    uint32_t max_workgroup_invocations = 0;
    std::array<uint32_t, 3> max_workgroup_count{};
    uint32_t max_push_constants_bytes = 0;
    uint32_t max_push_descriptors = 0;
    uint64_t max_storage_buffer_range = 0;
    uint64_t min_storage_buffer_offset_alignment = 0;
    uint64_t device_local_memory_bytes = 0;  // sum of device-local heaps

    DeviceFeatures features;

    // Required features this device lacks, each named ("VK_KHR_push_descriptor", "shaderInt64",
    // "Vulkan 1.3 (device has 1.2.198)"). Empty means vplkit can run on it.
    std::vector<std::string> missing;
    bool usable() const { return missing.empty(); }

    // Why this device was chosen (set on Context::info(); empty in enumerate_devices()).
    std::string reason;
};

// "1.3.230"
std::string version_string(uint32_t api_version);

// Names of the subgroup operations in `ops`, e.g. "basic vote arithmetic ballot".
std::string subgroup_operations_string(VkSubgroupFeatureFlags ops);

struct DeviceChoice {
    uint32_t index = 0;  // into the list given to choose_device (== DeviceInfo::index)
    std::string reason;  // "picked NVIDIA H100 (discrete GPU) over llvmpipe (CPU)"
};

// Picks a device from `devices` for `request`:
//   "" or "auto"        best usable device: discrete GPU > integrated > virtual > CPU (lavapipe)
//   "gpu"               best usable GPU; error when there is none
//   "cpu", "lavapipe"   the CPU device
//   "<n>"               device index n as listed by enumerate_devices()
//   anything else       the device whose name contains it (case-insensitive)
// `source` says where the request came from for messages (the environment variable, or the
// command line's device option).
// Throws Error naming the request and listing the devices when none matches, or naming the
// missing features when the requested device cannot run vplkit.
DeviceChoice choose_device(const std::vector<DeviceInfo>& devices, const std::string& request,
                           const std::string& source = "device option");

}  // namespace vplkit
