// Reading what a device has. Only what vkGetPhysicalDevice* reports; nothing is created.

#include "device_query.hpp"

#include "vplkit/error.hpp"

#include <algorithm>
#include <cstring>

namespace vplkit {

const char* device_type_name(DeviceType type) {
    switch (type) {
        case DeviceType::discrete_gpu:
            return "discrete GPU";
        case DeviceType::integrated_gpu:
            return "integrated GPU";
        case DeviceType::virtual_gpu:
            return "virtual GPU";
        case DeviceType::cpu:
            return "CPU";
        case DeviceType::other:
            break;
    }
    return "other";
}

std::string version_string(uint32_t api_version) {
    return std::to_string(VK_API_VERSION_MAJOR(api_version)) + "." + std::to_string(VK_API_VERSION_MINOR(api_version)) +
           "." + std::to_string(VK_API_VERSION_PATCH(api_version));
}

std::string subgroup_operations_string(VkSubgroupFeatureFlags ops) {
    static constexpr struct {
        VkSubgroupFeatureFlagBits bit;
        const char* name;
    } kNames[] = {
        {VK_SUBGROUP_FEATURE_BASIC_BIT, "basic"},
        {VK_SUBGROUP_FEATURE_VOTE_BIT, "vote"},
        {VK_SUBGROUP_FEATURE_ARITHMETIC_BIT, "arithmetic"},
        {VK_SUBGROUP_FEATURE_BALLOT_BIT, "ballot"},
        {VK_SUBGROUP_FEATURE_SHUFFLE_BIT, "shuffle"},
        {VK_SUBGROUP_FEATURE_SHUFFLE_RELATIVE_BIT, "shuffle_relative"},
        {VK_SUBGROUP_FEATURE_CLUSTERED_BIT, "clustered"},
        {VK_SUBGROUP_FEATURE_QUAD_BIT, "quad"},
    };
    std::string out;
    for (const auto& entry : kNames) {
        if (!(ops & entry.bit)) continue;
        if (!out.empty()) out += ' ';
        out += entry.name;
    }
    return out.empty() ? "none" : out;
}

namespace detail {

std::unordered_set<std::string> device_extensions(VkPhysicalDevice physical_device) {
    uint32_t count = 0;
    VPLKIT_CHECK(vkEnumerateDeviceExtensionProperties(physical_device, nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> properties(count);
    VPLKIT_CHECK(vkEnumerateDeviceExtensionProperties(physical_device, nullptr, &count, properties.data()));
    std::unordered_set<std::string> names;
    for (const auto& p : properties) names.insert(p.extensionName);
    return names;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
    uint32_t count = 0;
    VPLKIT_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    if (count > 0) VPLKIT_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    devices.resize(count);
    return devices;
}

static DeviceType to_device_type(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return DeviceType::discrete_gpu;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return DeviceType::integrated_gpu;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return DeviceType::virtual_gpu;
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return DeviceType::cpu;
        default:
            return DeviceType::other;
    }
}

DeviceInfo query_device(VkPhysicalDevice physical_device, uint32_t index) {
    DeviceInfo info;
    info.index = index;
    const auto extensions = device_extensions(physical_device);
    auto has = [&](const char* name) { return extensions.count(name) != 0; };

    VkPhysicalDeviceProperties core{};
    vkGetPhysicalDeviceProperties(physical_device, &core);
    info.name = core.deviceName;
    info.type = to_device_type(core.deviceType);
    info.type_name = device_type_name(info.type);
    info.vendor_id = core.vendorID;
    info.device_id = core.deviceID;
    info.api_version = core.apiVersion;
    info.api_version_string = version_string(core.apiVersion);
    info.timestamp_period_ns = core.limits.timestampPeriod;
    info.max_shared_memory_bytes = core.limits.maxComputeSharedMemorySize;
    for (int i = 0; i < 3; ++i) {
        info.max_workgroup_size[i] = core.limits.maxComputeWorkGroupSize[i];
        info.max_workgroup_count[i] = core.limits.maxComputeWorkGroupCount[i];
    }
    info.max_workgroup_invocations = core.limits.maxComputeWorkGroupInvocations;
    info.max_push_constants_bytes = core.limits.maxPushConstantsSize;
    info.max_storage_buffer_range = core.limits.maxStorageBufferRange;
    info.min_storage_buffer_offset_alignment = core.limits.minStorageBufferOffsetAlignment;
    info.driver_info = std::to_string(core.driverVersion);

    DeviceFeatures& f = info.features;
    f.vulkan_1_3 = core.apiVersion >= VK_API_VERSION_1_3;
    f.push_descriptor = has(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    f.ray_tracing_pipeline = has(VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME);
    f.acceleration_structure = has(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME);
    f.ray_query = has(VK_KHR_RAY_QUERY_EXTENSION_NAME);

    VkPhysicalDeviceMemoryProperties memory{};
    vkGetPhysicalDeviceMemoryProperties(physical_device, &memory);
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i) {
        if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            info.device_local_memory_bytes += memory.memoryHeaps[i].size;
    }

    // Vulkan 1.1-1.3 property and feature structs may only be chained for a device that has
    // that version, so a pre-1.3 device is described from the core structs alone: it is not
    // usable anyway, and the report says so.
    if (f.vulkan_1_3) {
        VkPhysicalDevicePushDescriptorPropertiesKHR push{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR};
        VkPhysicalDeviceVulkan13Properties p13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES};
        VkPhysicalDeviceVulkan12Properties p12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
        VkPhysicalDeviceVulkan11Properties p11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES};
        p11.pNext = &p12;
        p12.pNext = &p13;
        if (f.push_descriptor) p13.pNext = &push;
        VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p11};
        vkGetPhysicalDeviceProperties2(physical_device, &properties);
        info.driver_name = p12.driverName;
        info.driver_info = p12.driverInfo;
        info.subgroup_size = p11.subgroupSize;
        info.subgroup_operations = p11.subgroupSupportedOperations;
        info.subgroup_stages = p11.subgroupSupportedStages;
        info.min_subgroup_size = p13.minSubgroupSize;
        info.max_subgroup_size = p13.maxSubgroupSize;
        info.max_push_descriptors = f.push_descriptor ? push.maxPushDescriptors : 0;

        VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomic_float{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        f12.pNext = &f13;
        if (has(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME)) f13.pNext = &atomic_float;
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
        vkGetPhysicalDeviceFeatures2(physical_device, &features);
        f.synchronization2 = f13.synchronization2;
        f.shader_int64 = features.features.shaderInt64;
        f.shader_float64 = features.features.shaderFloat64;
        f.scalar_block_layout = f12.scalarBlockLayout;
        f.shader_buffer_int64_atomics = f12.shaderBufferInt64Atomics;
        f.shader_buffer_float32_atomic_add = atomic_float.shaderBufferFloat32AtomicAdd;
        f.shader_shared_float32_atomic_add = atomic_float.shaderSharedFloat32AtomicAdd;
        f.subgroup_size_control = f13.subgroupSizeControl;
        f.compute_full_subgroups = f13.computeFullSubgroups;
    } else {
        VkPhysicalDeviceFeatures features{};
        vkGetPhysicalDeviceFeatures(physical_device, &features);
        f.shader_int64 = features.shaderInt64;
        f.shader_float64 = features.shaderFloat64;
    }

    const bool compute_subgroups = (info.subgroup_stages & VK_SHADER_STAGE_COMPUTE_BIT) != 0;
    auto op = [&](VkSubgroupFeatureFlagBits bit) { return compute_subgroups && (info.subgroup_operations & bit); };
    f.subgroup_basic = op(VK_SUBGROUP_FEATURE_BASIC_BIT);
    f.subgroup_vote = op(VK_SUBGROUP_FEATURE_VOTE_BIT);
    f.subgroup_arithmetic = op(VK_SUBGROUP_FEATURE_ARITHMETIC_BIT);
    f.subgroup_ballot = op(VK_SUBGROUP_FEATURE_BALLOT_BIT);
    f.subgroup_shuffle = op(VK_SUBGROUP_FEATURE_SHUFFLE_BIT);
    f.subgroup_shuffle_relative = op(VK_SUBGROUP_FEATURE_SHUFFLE_RELATIVE_BIT);
    f.subgroup_clustered = op(VK_SUBGROUP_FEATURE_CLUSTERED_BIT);
    f.subgroup_quad = op(VK_SUBGROUP_FEATURE_QUAD_BIT);

    // One queue family does everything: the first with graphics, compute and timestamps.
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device, &family_count, families.data());
    const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < family_count; ++i) {
        if ((families[i].queueFlags & wanted) != wanted) continue;
        if (info.queue_family == UINT32_MAX || (info.timestamp_valid_bits == 0 && families[i].timestampValidBits > 0)) {
            info.queue_family = i;
            info.timestamp_valid_bits = families[i].timestampValidBits;
        }
    }
    f.timestamps = info.queue_family != UINT32_MAX && info.timestamp_valid_bits > 0 && core.limits.timestampPeriod > 0;

    if (!f.vulkan_1_3) info.missing.push_back("Vulkan 1.3 (device has " + info.api_version_string + ")");
    if (f.vulkan_1_3 && !f.synchronization2) info.missing.push_back("synchronization2");
    if (!f.push_descriptor) info.missing.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    if (!f.shader_int64) info.missing.push_back("shaderInt64");
    if (f.vulkan_1_3 && !f.scalar_block_layout) info.missing.push_back("scalarBlockLayout");
    if (info.queue_family == UINT32_MAX) {
        info.missing.push_back("a graphics+compute queue");
    } else if (!f.timestamps) {
        info.missing.push_back("timestamps on the graphics+compute queue");
    }
    return info;
}

}  // namespace detail
}  // namespace vplkit
