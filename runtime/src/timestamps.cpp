#include "timestamps.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"

namespace vplkit::detail {

TimestampQueries::TimestampQueries(const Context& context, uint32_t count) : context_(context), count_(count) {
    if (count_ == 0) return;
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = count_;
    VPLKIT_CHECK(vkCreateQueryPool(context_.device(), &info, nullptr, &pool_));
    context_.set_name(pool_, "vplkit pass timestamps");
}

TimestampQueries::~TimestampQueries() {
    if (pool_) vkDestroyQueryPool(context_.device(), pool_, nullptr);
}

void TimestampQueries::reset(VkCommandBuffer cmd) const {
    if (pool_) vkCmdResetQueryPool(cmd, pool_, 0, count_);
}

void TimestampQueries::write(VkCommandBuffer cmd, uint32_t query) const {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, query);
}

std::vector<double> TimestampQueries::pair_durations_ms() const {
    std::vector<double> durations;
    if (count_ < 2) return durations;
    std::vector<uint64_t> ticks(count_);
    VPLKIT_CHECK(vkGetQueryPoolResults(context_.device(), pool_, 0, count_, ticks.size() * sizeof(uint64_t),
                                       ticks.data(), sizeof(uint64_t),
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    const DeviceInfo& info = context_.info();
    // Only the low timestampValidBits bits count; masking the difference also handles a wrap.
    const uint64_t mask =
        info.timestamp_valid_bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << info.timestamp_valid_bits) - 1;
    for (uint32_t i = 0; i + 1 < count_; i += 2) {
        const uint64_t elapsed = (ticks[i + 1] - ticks[i]) & mask;
        durations.push_back(double(elapsed) * double(info.timestamp_period_ns) * 1e-6);
    }
    return durations;
}

}  // namespace vplkit::detail
