// required_device_features and its check: one list of what the kit's shaders and recording use
// (SPIR-V capabilities: Shader, Int64, ImageQuery, PhysicalStorageBufferAddresses; scalar block layout;
// synchronization2 barriers; dynamic rendering in the raster stages; push descriptors), so README, headers and samples
// cite one function instead of three lists.

#include "vplkit/stages/device_requirements.hpp"

#include "vplkit/error.hpp"

#include <algorithm>
#include <cstddef>

namespace vplkit::stages {
namespace {

std::string version_name(uint32_t version) {
    return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version));
}

// Every member of these structs from `first` on is a VkBool32 feature flag: OR `from`'s into `into`.
template <class Features>
void add_flags(Features& into, const Features& from, size_t first) {
    static_assert((sizeof(Features) % sizeof(VkBool32)) == 0);
    auto* to = reinterpret_cast<VkBool32*>(reinterpret_cast<char*>(&into) + first);
    const auto* flags = reinterpret_cast<const VkBool32*>(reinterpret_cast<const char*>(&from) + first);
    for (size_t i = 0; i < (sizeof(Features) - first) / sizeof(VkBool32); ++i) to[i] = to[i] | flags[i];
}

const char* feature_struct_name(VkStructureType type) {
    switch (type) {
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2:
            return "VkPhysicalDeviceFeatures2";
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES:
            return "VkPhysicalDeviceVulkan12Features";
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES:
            return "VkPhysicalDeviceVulkan13Features";
        default:
            return nullptr;
    }
}

}  // namespace

VkPhysicalDeviceFeatures2* DeviceRequirements::chain(void* next) {
    for (auto* s = static_cast<const VkBaseInStructure*>(next); s != nullptr; s = s->pNext) {
        if (const char* name = feature_struct_name(s->sType)) {
            throw Error(std::string("DeviceRequirements::chain: your feature chain already holds a ") + name +
                        " (a pNext chain may hold each type once): pass it to merge_into, which adds the kit's "
                        "flags to yours");
        }
    }
    features.pNext = &features12;
    features12.pNext = &features13;
    features13.pNext = next;
    return &features;
}

void* DeviceRequirements::merge_into(void* your_chain) {
    bool has[3] = {false, false, false};  // Features2, Vulkan12Features, Vulkan13Features
    for (auto* s = static_cast<VkBaseOutStructure*>(your_chain); s != nullptr; s = s->pNext) {
        if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2) {
            auto& yours = reinterpret_cast<VkPhysicalDeviceFeatures2*>(s)->features;
            add_flags(yours, features.features, 0);
            has[0] = true;
        } else if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES) {
            add_flags(*reinterpret_cast<VkPhysicalDeviceVulkan12Features*>(s), features12,
                      offsetof(VkPhysicalDeviceVulkan12Features, samplerMirrorClampToEdge));
            has[1] = true;
        } else if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES) {
            add_flags(*reinterpret_cast<VkPhysicalDeviceVulkan13Features*>(s), features13,
                      offsetof(VkPhysicalDeviceVulkan13Features, robustImageAccess));
            has[2] = true;
        }
    }
    void* head = your_chain;
    if (!has[2]) {
        features13.pNext = head;
        head = &features13;
    }
    if (!has[1]) {
        features12.pNext = head;
        head = &features12;
    }
    if (!has[0]) {
        features.pNext = head;
        head = &features;
    }
    return head;
}

DeviceRequirements required_device_features() {
    DeviceRequirements needs;
    needs.extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    needs.features.features.shaderInt64 = VK_TRUE;
    needs.features12.scalarBlockLayout = VK_TRUE;
    needs.features12.bufferDeviceAddress = VK_TRUE;
    needs.features13.synchronization2 = VK_TRUE;
    needs.features13.dynamicRendering = VK_TRUE;
    needs.chain();
    return needs;
}

DeviceSupport DeviceSupport::query(VkPhysicalDevice physical_device) {
    DeviceSupport support;
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(physical_device, &properties);
    support.api_version = properties.apiVersion;
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(physical_device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(physical_device, nullptr, &count, extensions.data());
    for (const VkExtensionProperties& e : extensions) support.extensions.emplace_back(e.extensionName);
    // The 1.2/1.3 structs may only be queried on a device that has that version.
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    if (support.api_version >= VK_API_VERSION_1_3) {
        features.pNext = &support.features12;
        support.features12.pNext = &support.features13;
    } else if (support.api_version >= VK_API_VERSION_1_2) {
        features.pNext = &support.features12;
    }
    vkGetPhysicalDeviceFeatures2(physical_device, &features);
    support.features = features.features;
    support.features12.pNext = nullptr;
    support.features13.pNext = nullptr;
    return support;
}

std::vector<std::string> missing_device_features(const DeviceSupport& support, const DeviceRequirements& needs) {
    std::vector<std::string> missing;
    if (support.api_version < needs.api_version) {
        missing.push_back("Vulkan " + version_name(needs.api_version) + " (the device has " +
                          version_name(support.api_version) + ")");
    }
    for (const char* extension : needs.extensions) {
        if (std::find(support.extensions.begin(), support.extensions.end(), extension) == support.extensions.end())
            missing.push_back(std::string("extension ") + extension);
    }
    auto check = [&](VkBool32 needed, VkBool32 offered, const char* name, const char* version) {
        if (needed && !offered) missing.push_back(std::string("feature ") + name + " (Vulkan " + version + ")");
    };
    // Every flag that required_device_features() sets.
    check(needs.features.features.shaderInt64, support.features.shaderInt64, "shaderInt64", "1.0");
    check(needs.features12.scalarBlockLayout, support.features12.scalarBlockLayout, "scalarBlockLayout", "1.2");
    check(needs.features12.bufferDeviceAddress, support.features12.bufferDeviceAddress, "bufferDeviceAddress", "1.2");
    check(needs.features13.synchronization2, support.features13.synchronization2, "synchronization2", "1.3");
    check(needs.features13.dynamicRendering, support.features13.dynamicRendering, "dynamicRendering", "1.3");
    return missing;
}

std::vector<std::string> missing_device_features(VkPhysicalDevice physical_device, const DeviceRequirements& needs) {
    return missing_device_features(DeviceSupport::query(physical_device), needs);
}

}  // namespace vplkit::stages
