#pragma once
// One frame's GPU work as one command buffer: every stage records into `passes`; the resources
// a stage creates for the frame are held until the submission has run; what the host reads
// back (counters, counts, the notes they make) waits in after_run() until then. So nothing the
// GPU computes in a frame is read by the host before the frame's last pass: the VPL counts stay
// on the GPU (stages/element_count.hpp) from the VPL source to the samplers.

#include "vplkit/pass_list.hpp"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace vplkit {

class FrameRecording {
public:
    explicit FrameRecording(std::string name) : passes_(std::move(name)) {}

    PassList& passes() { return passes_; }

    // Keeps `value` alive (and at one address: images track their layout) until submit() ends.
    template <class T>
    T& hold(T value) {
        auto held = std::make_shared<T>(std::move(value));
        T& ref = *held;
        held_.push_back(std::move(held));
        return ref;
    }

    // Runs after the submission, in the order added.
    void after_run(std::function<void()> read) { after_.push_back(std::move(read)); }

    // Submits what was recorded (one command buffer) and waits, appends its timings, runs the
    // after-run reads, then releases the held resources. The recording can be used again.
    void submit(Context& context, std::vector<PassTiming>& timings) {
        passes_.run(context);
        timings.insert(timings.end(), passes_.timings().begin(), passes_.timings().end());
        passes_.clear();
        std::vector<std::function<void()>> after = std::move(after_);
        after_.clear();
        for (const auto& read : after) read();
        held_.clear();
    }

    bool empty() const { return passes_.empty() && after_.empty(); }

private:
    PassList passes_;
    std::vector<std::function<void()>> after_;
    std::vector<std::shared_ptr<void>> held_;
};

}  // namespace vplkit
