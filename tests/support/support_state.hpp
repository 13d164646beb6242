#pragma once
// Private to the test support library: state shared by context.cpp and main.cpp.

#include "vplkit/context.hpp"
#include "vplkit/validation.hpp"

#include <memory>
#include <mutex>
#include <vector>

namespace vplkit::test::detail {

struct State {
    std::mutex mutex;
    std::unique_ptr<Context> shared;
    int capture_depth = 0;
    std::vector<ValidationMessage> captured;
    std::vector<ValidationMessage> outside_tests;  // e.g. leaks reported when the context dies
};

State& state();
void destroy_shared_context();

}  // namespace vplkit::test::detail
