#pragma once
// The check every "a view past maxStorageBufferRange is refused" test makes: recording the step
// throws vplkit::Error naming the view (and the step, where given) and the device's limit,
// instead of binding it invalidly.

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"

#include <doctest/doctest.h>

#include <initializer_list>
#include <string>

namespace vplkit::test {

template <class Record>
void check_refused_past_range(const Context& ctx, std::initializer_list<const char*> names, Record&& record) {
    try {
        record();
        FAIL("a view past maxStorageBufferRange was bound");
    } catch (const Error& e) {
        const std::string message = e.what();
        for (const char* name : names) CHECK(message.find(name) != std::string::npos);
        CHECK(message.find("maxStorageBufferRange " + std::to_string(ctx.info().max_storage_buffer_range)) !=
              std::string::npos);
    }
}

}  // namespace vplkit::test
