#pragma once
// Errors: every failure the runtime can detect becomes a vplkit::Error whose message names the
// problem (the failing Vulkan call and its VkResult, the missing feature, the bad argument).

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace vplkit {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message, VkResult result = VK_SUCCESS)
        : std::runtime_error(message), result_(result) {}

    // The VkResult that caused the error, VK_SUCCESS when it did not come from a Vulkan call.
    VkResult result() const { return result_; }

private:
    VkResult result_;
};

// "VK_ERROR_OUT_OF_DEVICE_MEMORY"; "VkResult(-123)" for a value this build does not know.
std::string result_name(VkResult result);

// Throws Error("<what> failed: <VK_...>") unless result is VK_SUCCESS.
// Other non-error codes (VK_INCOMPLETE, VK_TIMEOUT, ...) also throw: a runtime call that can
// legitimately return them handles them itself instead of going through check().
void check(VkResult result, const char* what);

}  // namespace vplkit

// VPLKIT_CHECK(vkCreateBuffer(device, &info, nullptr, &buffer)): the error message carries the
// call's source text, so a failure names the call without a hand-written description.
#define VPLKIT_CHECK(call) ::vplkit::check((call), #call)
