#include "vplkit_test/context.hpp"

#include "support_state.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>

namespace vplkit::test {
namespace detail {

State& state() {
    static State s;
    return s;
}

void destroy_shared_context() {
    state().shared.reset();
}

}  // namespace detail

std::string test_device() {
    const char* env = std::getenv("VPLKIT_TEST_DEVICE");
    return env && *env ? env : "cpu";
}

static bool sync_validation_wanted() {
    const char* env = std::getenv("VPLKIT_TEST_SYNC_VALIDATION");
    return !(env && std::string(env) == "0");
}

ContextOptions context_options(std::string device) {
    ContextOptions options;
    options.validation = true;
    options.synchronization_validation = sync_validation_wanted();
    options.device = device;
    options.on_validation_message = report_validation_message;
    return options;
}

Context& context() {
    auto& s = detail::state();
    if (!s.shared) s.shared = Context::create(context_options(test_device()));
    return *s.shared;
}

void report_validation_message(const ValidationMessage& message) {
    auto& s = detail::state();
    {
        std::lock_guard lock(s.mutex);
        if (s.capture_depth > 0) {
            s.captured.push_back(message);
            return;
        }
        if (!doctest::is_running_in_test) {
            s.outside_tests.push_back(message);
            std::fprintf(stderr, "vplkit test: outside any test case: %s\n", to_string(message).c_str());
            return;
        }
    }
    // Called from inside the Vulkan call the test made, on the test's thread: the failure lands in
    // the running test case (and subcase), with the layer's message as its text.
    FAIL_CHECK(to_string(message));
}

ValidationCapture::ValidationCapture() {
    auto& s = detail::state();
    std::lock_guard lock(s.mutex);
    if (s.capture_depth++ == 0) s.captured.clear();
}

ValidationCapture::~ValidationCapture() {
    auto& s = detail::state();
    std::lock_guard lock(s.mutex);
    --s.capture_depth;
}

std::vector<ValidationMessage> ValidationCapture::messages() const {
    auto& s = detail::state();
    std::lock_guard lock(s.mutex);
    return s.captured;
}

bool ValidationCapture::contains(std::string_view needle) const {
    for (const auto& m : messages()) {
        if (m.id_name.find(needle) != std::string::npos || m.text.find(needle) != std::string::npos) return true;
    }
    return false;
}

}  // namespace vplkit::test
