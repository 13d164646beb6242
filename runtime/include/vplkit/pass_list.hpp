#pragma once
// PassList: a StepList (vplkit/steps.hpp) that the runtime runs. Passes are recorded in
// the order they were added; each pass declares which buffers and images it touches and how, and
// run() inserts a synchronization2 barrier before a pass only where a declared use conflicts with
// an earlier one (read-after-write, write-after-write, write-after-read, or an image layout
// change), then submits, waits and reads back a GPU time per pass.
//
//   vplkit::PassList passes;
//   passes.add("keys", {Use::read(vpls), Use::write(keys)}, [&](VkCommandBuffer cmd) { ... });
//   passes.add("sort", {Use::read_write(keys)}, [&](VkCommandBuffer cmd) { ... });
//   passes.run(ctx);            // one command buffer, submitted and waited for
//   for (auto& t : passes.timings()) std::printf("%s %.3f ms\n", t.name.c_str(), t.gpu_ms);
//
// Buffers and Images convert to the views a Use names. Resources are tracked whole (no
// sub-ranges). Tracking starts fresh at every run(): the runtime ends every submission with a
// full memory barrier, so nothing from an earlier submission needs synchronizing. Image layouts
// persist in the Image objects across runs (an Image must stay at its address until run()).

#include "vplkit/steps.hpp"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace vplkit {

class Context;

struct PassTiming {
    std::string name;
    double gpu_ms = 0.0;  // GPU time from the end of everything before the pass to its own end
    uint32_t tag = 0;     // the pass's Step::tag
    // The command buffer the pass was recorded in: one number per run() in this process, so
    // passes with the same number went to the GPU together, with no host work in between.
    uint64_t submission = 0;
};

class PassList : public StepList {
public:
    // `name` labels the whole command buffer in debuggers.
    explicit PassList(std::string name = "vplkit passes") : name_(std::move(name)) {}

    // Records every pass into one command buffer with the barriers the uses call for, a debug
    // label and a pair of timestamps around each pass, submits it and waits. Can be called again.
    void run(Context& context);

    void clear() override;

    // Of the last run(): one entry per pass, in order.
    const std::vector<PassTiming>& timings() const { return timings_; }
    double total_gpu_ms() const;
    // Of the last run(): every barrier, in recording order (buffer and image barriers counted
    // one by one; several of them before one pass share one vkCmdPipelineBarrier2 call).
    const std::vector<BarrierRecord>& barriers() const { return barriers_; }
    size_t barrier_count() const { return barriers_.size(); }
    // Number of vkCmdPipelineBarrier2 calls of the last run (not counting the final host barrier).
    size_t pipeline_barrier_count() const;
    // Barriers of the last run, one describe() line each.
    std::string describe_barriers() const;

private:
    std::string name_;
    std::vector<PassTiming> timings_;
    std::vector<BarrierRecord> barriers_;
};

}  // namespace vplkit
