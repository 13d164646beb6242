// Context: instance -> chosen device -> one queue, plus the few long-lived objects every stage
// shares (command pool, pipeline cache, pipelines of generated shader types).

#include "vplkit/context.hpp"

#include "device_query.hpp"
#include "instance.hpp"
#include "validation_sink.hpp"
#include "vplkit/barriers.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/stages/device_requirements.hpp"

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace vplkit {
namespace {

struct DeviceRequest {
    std::string request;
    std::string source;
};

// The option wins; the environment applies only when the program left the choice to vplkit.
DeviceRequest device_request(const ContextOptions& options) {
    if (!options.device.empty()) return {options.device, "device option"};
    if (const char* env = std::getenv("VPLKIT_DEVICE"); env && *env) return {env, "VPLKIT_DEVICE"};
    return {"", "default"};
}

}  // namespace

std::unique_ptr<Context> Context::create(const ContextOptions& options) {
    std::unique_ptr<Context> context(new Context());
    try {
        context->init(options);
    } catch (...) {
        context->destroy();
        throw;
    }
    return context;
}

std::vector<DeviceInfo> Context::enumerate_devices() {
    const auto created = detail::create_instance(nullptr, false);
    std::vector<DeviceInfo> infos;
    try {
        const auto devices = detail::physical_devices(created.instance);
        for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(detail::query_device(devices[i], i));
    } catch (...) {
        vkDestroyInstance(created.instance, nullptr);
        throw;
    }
    vkDestroyInstance(created.instance, nullptr);
    return infos;
}

void Context::init(const ContextOptions& options) {
    options_ = options;
    if (options_.synchronization_validation && !options_.validation) {
        throw Error("vplkit: synchronization_validation needs validation = true");
    }
    if (options_.validation) {
        validation_ = std::make_unique<detail::ValidationSink>();
        validation_->callback = options_.on_validation_message;
    }

    const auto created =
        detail::create_instance(validation_.get(), options_.synchronization_validation, options_.instance_extensions);
    instance_ = created.instance;
    if (validation_) messenger_ = detail::create_messenger(instance_, validation_.get());

    const auto physical = detail::physical_devices(instance_);
    std::vector<DeviceInfo> infos;
    for (uint32_t i = 0; i < physical.size(); ++i) infos.push_back(detail::query_device(physical[i], i));
    const auto [request, source] = device_request(options_);
    const DeviceChoice choice = choose_device(infos, request, source);
    physical_device_ = physical[choice.index];
    info_ = infos[choice.index];
    info_.reason = choice.reason;
    queue_family_ = info_.queue_family;
    vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_properties_);

    // The features every stage needs, as stages/device_requirements.hpp states them (the one
    // list a foreign renderer enables too), plus optional ones whenever the device has them, so
    // the runtime can use them after checking info().features. Nothing is enabled that costs
    // performance (robustBufferAccess stays off).
    VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomic_float{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
    VkPhysicalDeviceVulkan13Features s13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features s12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &s13};
    VkPhysicalDeviceVulkan11Features s11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &s12};
    const auto extensions = detail::device_extensions(physical_device_);
    const bool has_atomic_float = extensions.count(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME) != 0;
    if (has_atomic_float) s13.pNext = &atomic_float;
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &s11};
    vkGetPhysicalDeviceFeatures2(physical_device_, &supported);

    stages::DeviceRequirements needs = stages::required_device_features();
    VkPhysicalDeviceVulkan11Features e11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceFeatures2& enable = *needs.chain(&e11);
    VkPhysicalDeviceVulkan12Features& e12 = needs.features12;
    VkPhysicalDeviceVulkan13Features& e13 = needs.features13;
    const VkPhysicalDeviceFeatures& core = supported.features;
    enable.features.shaderFloat64 = core.shaderFloat64;
    enable.features.shaderInt16 = core.shaderInt16;
    enable.features.fragmentStoresAndAtomics = core.fragmentStoresAndAtomics;
    enable.features.vertexPipelineStoresAndAtomics = core.vertexPipelineStoresAndAtomics;
    enable.features.shaderStorageImageReadWithoutFormat = core.shaderStorageImageReadWithoutFormat;
    enable.features.shaderStorageImageWriteWithoutFormat = core.shaderStorageImageWriteWithoutFormat;
    e11.storageBuffer16BitAccess = s11.storageBuffer16BitAccess;
    e11.shaderDrawParameters = s11.shaderDrawParameters;
    e12.shaderBufferInt64Atomics = s12.shaderBufferInt64Atomics;
    e12.shaderSharedInt64Atomics = s12.shaderSharedInt64Atomics;
    e12.storageBuffer8BitAccess = s12.storageBuffer8BitAccess;
    e12.shaderInt8 = s12.shaderInt8;
    e12.shaderFloat16 = s12.shaderFloat16;
    e12.hostQueryReset = s12.hostQueryReset;
    e12.vulkanMemoryModel = s12.vulkanMemoryModel;
    e12.vulkanMemoryModelDeviceScope = s12.vulkanMemoryModelDeviceScope;
    e12.shaderSubgroupExtendedTypes = s12.shaderSubgroupExtendedTypes;
    e12.timelineSemaphore = s12.timelineSemaphore;
    e13.subgroupSizeControl = s13.subgroupSizeControl;
    e13.computeFullSubgroups = s13.computeFullSubgroups;
    e13.maintenance4 = s13.maintenance4;
    std::vector<const char*> device_extensions = needs.extensions;
    if (has_atomic_float) {
        atomic_float.pNext = nullptr;  // all supported float-atomic features, as queried
        e11.pNext = &atomic_float;
        device_extensions.push_back(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
    }
    // The spec requires enabling it wherever it is offered (MoltenVK).
    if (extensions.count("VK_KHR_portability_subset")) device_extensions.push_back("VK_KHR_portability_subset");
    for (const std::string& name : options_.device_extensions) {
        if (!extensions.count(name)) {
            throw Error("vplkit: the device " + info_.name + " does not offer the extension " + name +
                        " (asked for in device_extensions)");
        }
        bool listed = false;
        for (const char* e : device_extensions) listed = listed || name == e;
        if (!listed) device_extensions.push_back(name.c_str());
    }

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &enable};
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    device_info.enabledExtensionCount = uint32_t(device_extensions.size());
    device_info.ppEnabledExtensionNames = device_extensions.data();
    VPLKIT_CHECK(vkCreateDevice(physical_device_, &device_info, nullptr, &device_));
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    if (created.debug_utils) {
        set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
        begin_label_ = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
        end_label_ = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
        if (!set_object_name_ || !begin_label_ || !end_label_)
            set_object_name_ = nullptr, begin_label_ = nullptr, end_label_ = nullptr;
    }

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    VPLKIT_CHECK(vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_));

    VkPipelineCacheCreateInfo cache_info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    VPLKIT_CHECK(vkCreatePipelineCache(device_, &cache_info, nullptr, &pipeline_cache_));

    set_name(queue_, "vplkit queue");
    set_name(command_pool_, "vplkit one-shot pool");
    set_name(pipeline_cache_, "vplkit pipeline cache");
    attach(device_, stages::Limits::query(physical_device_), pipeline_cache_);
}

Context::~Context() {
    destroy();
}

stages::ScratchBuffer Context::create_scratch_buffer(VkDeviceSize bytes, const std::string& name) {
    auto buffer = std::make_shared<Buffer>(
        Buffer::create(*this, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, name));
    return {*buffer, buffer};
}

void Context::destroy() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        destroy_pipelines();
        if (pipeline_cache_) vkDestroyPipelineCache(device_, pipeline_cache_, nullptr);
        if (command_pool_) vkDestroyCommandPool(device_, command_pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    pipeline_cache_ = VK_NULL_HANDLE;
    command_pool_ = VK_NULL_HANDLE;
    device_ = VK_NULL_HANDLE;
    if (instance_) {
        detail::destroy_messenger(instance_, messenger_);
        vkDestroyInstance(instance_, nullptr);
    }
    messenger_ = VK_NULL_HANDLE;
    instance_ = VK_NULL_HANDLE;
}

uint64_t Context::validation_message_count() const {
    return validation_ ? validation_->count.load(std::memory_order_relaxed) : 0;
}

void Context::set_name(VkObjectType type, uint64_t handle, std::string_view name) const {
    if (!set_object_name_ || handle == 0 || name.empty()) return;
    const std::string text(name);
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = text.c_str();
    set_object_name_(device_, &info);
}

void Context::begin_label(VkCommandBuffer cmd, std::string_view name) const {
    if (!begin_label_) return;
    const std::string text(name);
    VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    label.pLabelName = text.c_str();
    begin_label_(cmd, &label);
}

void Context::end_label(VkCommandBuffer cmd) const {
    if (end_label_) end_label_(cmd);
}

void Context::one_shot(const std::function<void(VkCommandBuffer)>& record) {
    // The pool and the queue need external synchronization; recursion (an upload from inside a
    // recording callback) is allowed because the lock is recursive and each call has its own
    // command buffer and fence.
    std::lock_guard lock(submit_mutex_);

    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = command_pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VPLKIT_CHECK(vkAllocateCommandBuffers(device_, &alloc, &cmd));
    VkFence fence = VK_NULL_HANDLE;
    auto cleanup = [&] {
        if (fence) vkDestroyFence(device_, fence, nullptr);
        vkFreeCommandBuffers(device_, command_pool_, 1, &cmd);
    };

    try {
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        VPLKIT_CHECK(vkBeginCommandBuffer(cmd, &begin));
        record(cmd);
        // Device writes -> host reads and every later command, including later submissions: the
        // contract that lets download() and the next PassList start with no barrier of their own.
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_HOST_READ_BIT);
        VPLKIT_CHECK(vkEndCommandBuffer(cmd));

        VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VPLKIT_CHECK(vkCreateFence(device_, &fence_info, nullptr, &fence));
        VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
        cmd_info.commandBuffer = cmd;
        VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        submit.commandBufferInfoCount = 1;
        submit.pCommandBufferInfos = &cmd_info;
        VPLKIT_CHECK(vkQueueSubmit2(queue_, 1, &submit, fence));
        VPLKIT_CHECK(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX));
    } catch (...) {
        // A failed submission may leave work queued that references the command buffer.
        vkDeviceWaitIdle(device_);
        cleanup();
        throw;
    }
    cleanup();
}

void Context::wait_idle() const {
    VPLKIT_CHECK(vkDeviceWaitIdle(device_));
}

}  // namespace vplkit
