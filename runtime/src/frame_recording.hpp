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

    // Keeps `value` alive (and at one address: images track their layout) as long as this
    // recording: work recorded after a submit() may still use it.
    template <class T>
    T& hold(T value) {
        return keep(std::move(value), held_);
    }

    // Keeps `value` alive until the next submit() has run, then frees it (memory the rest of the
    // frame does not need, such as one light's shadow map).
    template <class T>
    T& hold_until_submit(T value) {
        return keep(std::move(value), transient_);
    }

    // Runs after the submission, in the order added.
    void after_run(std::function<void()> read) { after_.push_back(std::move(read)); }

    // Submits what was recorded (one command buffer) and waits, appends its timings, runs the
    // after-run reads, then frees what hold_until_submit kept. The recording can be used again.
    void submit(Context& context, std::vector<PassTiming>& timings) {
        passes_.run(context);
        timings.insert(timings.end(), passes_.timings().begin(), passes_.timings().end());
        passes_.clear();
        std::vector<std::function<void()>> after = std::move(after_);
        after_.clear();
        for (const auto& read : after) read();
        transient_.clear();
    }

    bool empty() const { return passes_.empty() && after_.empty(); }

private:
    template <class T>
    static T& keep(T value, std::vector<std::shared_ptr<void>>& into) {
        auto kept = std::make_shared<T>(std::move(value));
        T& ref = *kept;
        into.push_back(std::move(kept));
        return ref;
    }

    PassList passes_;
    std::vector<std::function<void()>> after_;
    std::vector<std::shared_ptr<void>> held_;
    std::vector<std::shared_ptr<void>> transient_;
};

}  // namespace vplkit
