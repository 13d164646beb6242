// The instance: Vulkan 1.3, debug utils whenever the loader has it (object names and labels are
// cheap and make validation messages readable), the validation layer only when asked.

#include "instance.hpp"

#include "validation_sink.hpp"
#include "vplkit/error.hpp"

#include <cstring>
#include <string>
#include <vector>

namespace vplkit::detail {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool layer_installed(const char* name) {
    uint32_t count = 0;
    VPLKIT_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
    std::vector<VkLayerProperties> layers(count);
    VPLKIT_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
    for (const auto& layer : layers) {
        if (std::strcmp(layer.layerName, name) == 0) return true;
    }
    return false;
}

bool has_instance_extension(const char* layer, const char* name) {
    uint32_t count = 0;
    VPLKIT_CHECK(vkEnumerateInstanceExtensionProperties(layer, &count, nullptr));
    std::vector<VkExtensionProperties> extensions(count);
    VPLKIT_CHECK(vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data()));
    for (const auto& e : extensions) {
        if (std::strcmp(e.extensionName, name) == 0) return true;
    }
    return false;
}

}  // namespace

InstanceResult create_instance(ValidationSink* sink, bool synchronization_validation,
                               const std::vector<std::string>& extra) {
    uint32_t loader_version = VK_API_VERSION_1_0;
    VPLKIT_CHECK(vkEnumerateInstanceVersion(&loader_version));
    if (loader_version < VK_API_VERSION_1_3) {
        throw Error("vplkit: the Vulkan loader supports Vulkan " +
                    std::to_string(VK_API_VERSION_MAJOR(loader_version)) + "." +
                    std::to_string(VK_API_VERSION_MINOR(loader_version)) + "; vplkit needs 1.3 (update libvulkan1)");
    }

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    InstanceResult result;
    result.debug_utils = has_instance_extension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "vplkit";
    app.pEngineName = "vplkit";
    app.apiVersion = VK_API_VERSION_1_3;

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;

    VkDebugUtilsMessengerCreateInfoEXT messenger_info{};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    const VkValidationFeatureEnableEXT sync_enable = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;

    if (sink) {
        if (!layer_installed(kValidationLayer)) {
            throw Error(std::string("vplkit: validation requested but ") + kValidationLayer +
                        " is not installed (Debian 12 package 'vulkan-validationlayers')");
        }
        layers.push_back(kValidationLayer);
        // The layer itself provides VK_EXT_debug_utils when the loader does not.
        if (!result.debug_utils)
            result.debug_utils = has_instance_extension(kValidationLayer, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        if (!result.debug_utils) throw Error("vplkit: validation requested but VK_EXT_debug_utils is not available");
        // Chained so that messages about vkCreateInstance/vkDestroyInstance themselves arrive too.
        messenger_info = messenger_create_info(sink);
        info.pNext = &messenger_info;
        if (synchronization_validation) {
            if (!has_instance_extension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
                throw Error("vplkit: synchronization validation requested but the validation layer lacks " +
                            std::string(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME));
            }
            extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
            features.enabledValidationFeatureCount = 1;
            features.pEnabledValidationFeatures = &sync_enable;
            features.pNext = info.pNext;
            info.pNext = &features;
        }
    }
    if (result.debug_utils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    for (const std::string& name : extra) {
        if (!has_instance_extension(nullptr, name.c_str())) {
            throw Error("vplkit: the Vulkan loader does not offer the instance extension " + name +
                        " (asked for in instance_extensions)");
        }
        bool listed = false;
        for (const char* e : extensions) listed = listed || name == e;
        if (!listed) extensions.push_back(name.c_str());
    }

    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VPLKIT_CHECK(vkCreateInstance(&info, nullptr, &result.instance));
    return result;
}

}  // namespace vplkit::detail
