#pragma once
// Test support: the shared Vulkan context every test runs on, and the rule that any validation
// message fails the test during which it was emitted.
//
// The context is created on first use with the validation layer and synchronization validation
// on, on lavapipe ("cpu") unless the environment variable VPLKIT_TEST_DEVICE names another
// device (same syntax as VPLKIT_DEVICE: gpu, cpu, an index or part of a name).
// VPLKIT_TEST_SYNC_VALIDATION=0 turns synchronization validation off (it is slower).

#include "vplkit/context.hpp"
#include "vplkit/validation.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace vplkit::test {

// The shared context (created on first call; a creation failure throws vplkit::Error).
Context& context();

// Options for a test that needs a context of its own: validation on, and messages routed the
// same way as the shared context's (they fail the running test).
ContextOptions context_options(std::string device = "");

// The device tests run on: VPLKIT_TEST_DEVICE, or "cpu".
std::string test_device();

// Where every test context's validation messages go: inside a test case they fail it (with the
// message as the failure text) unless a ValidationCapture is active; outside any test case
// they are printed and make the test program exit with a failure.
void report_validation_message(const ValidationMessage& message);

// While alive, validation messages are collected here instead of failing the test: for tests
// that provoke a message on purpose and check it arrived.
class ValidationCapture {
public:
    ValidationCapture();
    ~ValidationCapture();
    ValidationCapture(const ValidationCapture&) = delete;
    ValidationCapture& operator=(const ValidationCapture&) = delete;

    std::vector<ValidationMessage> messages() const;
    // Whether a captured message's id name or text contains `needle`.
    bool contains(std::string_view needle) const;
};

}  // namespace vplkit::test
