// The debug messenger: turns validation-layer callbacks into ValidationMessages, counts them
// and hands them to the user's callback (tests turn each one into a failure).

#include "validation_sink.hpp"

#include "vplkit/error.hpp"

#include <cstdio>
#include <string>

namespace vplkit {

const char* severity_name(ValidationMessage::Severity severity) {
    return severity == ValidationMessage::Severity::error ? "error" : "warning";
}

std::string to_string(const ValidationMessage& message) {
    std::string out = std::string("[validation ") + severity_name(message.severity) + "] ";
    if (!message.id_name.empty()) out += message.id_name + ": ";
    out += message.text;
    return out;
}

namespace detail {
namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT types,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* sink = static_cast<ValidationSink*>(user);
    ValidationMessage message;
    message.severity = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)
                           ? ValidationMessage::Severity::error
                           : ValidationMessage::Severity::warning;
    message.types = types;
    if (data) {
        if (data->pMessageIdName) message.id_name = data->pMessageIdName;
        message.id_number = data->messageIdNumber;
        if (data->pMessage) message.text = data->pMessage;
    }
    sink->count.fetch_add(1, std::memory_order_relaxed);
    // An exception must not unwind through the layer: report it and carry on.
    try {
        if (sink->callback) {
            sink->callback(message);
        } else {
            std::fprintf(stderr, "vplkit: %s\n", to_string(message).c_str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vplkit: validation callback threw: %s\n", e.what());
    } catch (...) {
        std::fprintf(stderr, "vplkit: validation callback threw\n");
    }
    // VK_FALSE: the Vulkan call goes on as it would without the layer.
    return VK_FALSE;
}

}  // namespace

VkDebugUtilsMessengerCreateInfoEXT messenger_create_info(ValidationSink* sink) {
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = on_message;
    info.pUserData = sink;
    return info;
}

VkDebugUtilsMessengerEXT create_messenger(VkInstance instance, ValidationSink* sink) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    if (!create) throw Error("vplkit: validation requested but vkCreateDebugUtilsMessengerEXT is not available");
    const auto info = messenger_create_info(sink);
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VPLKIT_CHECK(create(instance, &info, nullptr, &messenger));
    return messenger;
}

void destroy_messenger(VkInstance instance, VkDebugUtilsMessengerEXT messenger) {
    if (!messenger) return;
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance, messenger, nullptr);
}

}  // namespace detail
}  // namespace vplkit
