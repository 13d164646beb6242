// required_device_features / missing_device_features: the one list of what the kit needs, and a
// check that names each missing item (a faked device) or nothing (the test device, which runs
// every stage).

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/stages/device_requirements.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

namespace {

// A device that has everything the kit asks for.
vplkit::stages::DeviceSupport complete_device() {
    vplkit::stages::DeviceSupport support;
    support.api_version = VK_API_VERSION_1_3;
    support.extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME, "VK_KHR_something_else"};
    support.features.shaderInt64 = VK_TRUE;
    support.features12.scalarBlockLayout = VK_TRUE;
    support.features12.bufferDeviceAddress = VK_TRUE;
    support.features13.synchronization2 = VK_TRUE;
    support.features13.dynamicRendering = VK_TRUE;
    return support;
}

}  // namespace

TEST_CASE("device requirements: the list is Vulkan 1.3, push descriptors and five features") {
    vplkit::stages::DeviceRequirements needs = vplkit::stages::required_device_features();
    CHECK(needs.api_version == VK_API_VERSION_1_3);
    REQUIRE(needs.extensions.size() == 1);
    CHECK(std::string(needs.extensions[0]) == VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    CHECK(needs.features.features.shaderInt64 == VK_TRUE);
    CHECK(needs.features12.scalarBlockLayout == VK_TRUE);
    CHECK(needs.features12.bufferDeviceAddress == VK_TRUE);
    CHECK(needs.features12.shaderBufferInt64Atomics == VK_FALSE);  // no shader uses 64-bit atomics
    CHECK(needs.features13.synchronization2 == VK_TRUE);
    // The chain links the three structs, ready for VkDeviceCreateInfo::pNext.
    const VkPhysicalDeviceFeatures2* chain = needs.chain();
    CHECK(chain->pNext == &needs.features12);
    CHECK(needs.features12.pNext == &needs.features13);
    CHECK(needs.features13.pNext == nullptr);
}

TEST_CASE("device requirements: the check names each missing feature, extension and version") {
    CHECK(vplkit::stages::missing_device_features(complete_device()).empty());

    vplkit::stages::DeviceSupport no_scalar = complete_device();
    no_scalar.features12.scalarBlockLayout = VK_FALSE;
    CHECK(vplkit::stages::missing_device_features(no_scalar) ==
          std::vector<std::string>{"feature scalarBlockLayout (Vulkan 1.2)"});

    vplkit::stages::DeviceSupport old = complete_device();
    old.api_version = VK_API_VERSION_1_2;
    old.extensions = {};
    old.features.shaderInt64 = VK_FALSE;
    old.features13 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    CHECK(vplkit::stages::missing_device_features(old) ==
          std::vector<std::string>{"Vulkan 1.3 (the device has 1.2)", "extension VK_KHR_push_descriptor",
                                   "feature shaderInt64 (Vulkan 1.0)", "feature synchronization2 (Vulkan 1.3)",
                                   "feature dynamicRendering (Vulkan 1.3)"});
}

TEST_CASE("device requirements: the test device has everything the kit needs") {
    const auto missing = vplkit::stages::missing_device_features(vplkit::test::context().physical_device());
    std::string named;
    for (const std::string& m : missing) named += m + "; ";
    CAPTURE(named);
    CHECK(missing.empty());
}

namespace {

// How many structs of `type` a pNext chain holds.
int count_in_chain(const void* head, VkStructureType type) {
    int n = 0;
    for (auto* s = static_cast<const VkBaseInStructure*>(head); s != nullptr; s = s->pNext) n += s->sType == type;
    return n;
}

}  // namespace

TEST_CASE("device requirements: merge_into adds the kit's flags to a renderer's own 1.3 struct, each type once") {
    // A renderer's chain: its own Vulkan 1.3 struct (dynamic rendering only) and a 1.1 one.
    VkPhysicalDeviceVulkan11Features mine11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceVulkan13Features mine13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES, &mine11};
    mine13.dynamicRendering = VK_TRUE;
    mine11.shaderDrawParameters = VK_TRUE;

    vplkit::stages::DeviceRequirements needs = vplkit::stages::required_device_features();
    CHECK_THROWS_WITH_AS(needs.chain(&mine13), doctest::Contains("already holds a VkPhysicalDeviceVulkan13Features"),
                         vplkit::Error);

    void* head = needs.merge_into(&mine13);
    CHECK(head == &needs.features);
    for (VkStructureType type :
         {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES,
          VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
          VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES}) {
        CAPTURE(type);
        CHECK(count_in_chain(head, type) == 1);
    }
    CHECK(mine13.synchronization2 == VK_TRUE);  // the kit's, in the renderer's struct
    CHECK(mine13.dynamicRendering == VK_TRUE);
    CHECK(mine13.robustImageAccess == VK_FALSE);    // nothing the kit did not ask for
    CHECK(mine11.shaderDrawParameters == VK_TRUE);  // the renderer's own, kept
    CHECK(needs.features12.scalarBlockLayout == VK_TRUE);

    // Nothing of the caller's: the same chain as chain().
    vplkit::stages::DeviceRequirements alone = vplkit::stages::required_device_features();
    CHECK(alone.merge_into(nullptr) == &alone.features);
    CHECK(alone.features.pNext == &alone.features12);
    CHECK(alone.features12.pNext == &alone.features13);
    CHECK(alone.features13.pNext == nullptr);
}

TEST_CASE(
    "device requirements: a device created from a renderer's chain merged with the kit's, no validation message") {
    vplkit::Context& context = vplkit::test::context();
    VkPhysicalDeviceVulkan13Features mine13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    mine13.dynamicRendering = VK_TRUE;
    vplkit::stages::DeviceRequirements needs = vplkit::stages::required_device_features();
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = 0;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, needs.merge_into(&mine13)};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    info.enabledExtensionCount = uint32_t(needs.extensions.size());
    info.ppEnabledExtensionNames = needs.extensions.data();
    VkDevice device = VK_NULL_HANDLE;
    REQUIRE(vkCreateDevice(context.physical_device(), &info, nullptr, &device) == VK_SUCCESS);
    vkDestroyDevice(device, nullptr);
}
