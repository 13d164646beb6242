#pragma once
// Private: a timestamp query pool for one submission, read back after the submission's wait.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace vplkit {
class Context;
}

namespace vplkit::detail {

class TimestampQueries {
public:
    TimestampQueries(const Context& context, uint32_t count);
    ~TimestampQueries();
    TimestampQueries(const TimestampQueries&) = delete;
    TimestampQueries& operator=(const TimestampQueries&) = delete;

    // Must be recorded before the first write(), outside any render pass.
    void reset(VkCommandBuffer cmd) const;
    // Written once every command recorded before it has completed (ALL_COMMANDS): the difference
    // of two such stamps is the time the commands between them added, overlap not double counted.
    void write(VkCommandBuffer cmd, uint32_t query) const;
    // After the submission completed: milliseconds between queries 2i and 2i+1, for each i.
    std::vector<double> pair_durations_ms() const;

private:
    const Context& context_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    uint32_t count_ = 0;
};

}  // namespace vplkit::detail
