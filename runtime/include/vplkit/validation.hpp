#pragma once
// What the validation layer reports, as the runtime hands it to ContextOptions::on_validation_message.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

namespace vplkit {

struct ValidationMessage {
    enum class Severity { warning, error };

    Severity severity = Severity::error;
    VkDebugUtilsMessageTypeFlagsEXT types = 0;  // general / validation / performance
    std::string id_name;                        // e.g. "VUID-vkCmdFillBuffer-dstOffset-00024"
    int32_t id_number = 0;
    std::string text;  // the layer's full message
};

// "error" / "warning".
const char* severity_name(ValidationMessage::Severity severity);

// One line for logs: "[validation error] VUID-...: text".
std::string to_string(const ValidationMessage& message);

}  // namespace vplkit
