#pragma once
// The runtime's side of SMC instant radiosity (stages/smc.hpp): the buffers of one VPL set that
// persists across frames, the sorter its updates use, the update counter, and the blocking read
// of what an update counted. The Renderer keeps one per scene while the SMC options stay the same.

#include "vplkit/buffer.hpp"
#include "vplkit/stages/smc.hpp"
#include "vplkit/stages/sort.hpp"

#include <cstdint>

namespace vplkit {
class Context;
}

namespace vplkit {

// What the last update counted (SmcCounters, smc.glsl).
struct SmcCounts {
    uint32_t vpls = 0;           // |Y| after the update
    uint32_t hits = 0;           // camera rays that found a reflecting surface
    uint32_t invalid = 0;        // VPLs whose mailbox failed
    uint32_t revalidated = 0;    // of those, found indirectly visible again by ray casts
    uint32_t candidates = 0;     // after resampling
    uint32_t strong = 0;         // M_strong (eq. 9)
    uint32_t min_moves = 0;      // M_min
    uint32_t still_invalid = 0;  // invalid after revalidation
    uint32_t removed = 0;        // VPLs taken out of Y
    uint32_t moved = 0;          // candidates put in (removed slots + appended)
    uint32_t cut_short = 0;      // radiosity paths the driver ended early
};

class SmcState {
public:
    // Buffers for `options` (Error for bad options); Y starts empty.
    static SmcState create(Context& context, const stages::SmcOptions& options);

    const stages::SmcOptions& options() const { return options_; }
    // Updates recorded so far (each draws its own random numbers).
    uint32_t updates() const { return updates_; }
    bool empty() const { return updates_ == 0; }

    // The scene was posed: the next update checks the VPLs against the moved geometry and
    // estimates every VPL's radiosity again (stages::SmcSceneChange). Moves add up until then.
    void scene_moved(bool geometry, bool lights) {
        change_.geometry = change_.geometry || geometry;
        change_.lights = change_.lights || lights;
    }

    // Adds one update (stages::add_smc_update_passes) for the frame of `gbuffer` and `view`.
    void add_update(Context& context, StepList& passes, const stages::GbufferViews& gbuffer,
                    const stages::CameraView& view, const stages::SmcScene& scene);
    // Blocking read of the last update's counts (after its passes ran). Throws Error when the
    // driver cut radiosity paths short (lavapipe's loop limit): the estimates would be low.
    SmcCounts read_counts() const;
    // The Vpl buffer the gathers read (its first read_counts().vpls entries).
    const Buffer& vpls() const { return vpls_; }
    // The SmcCounters the updates write (vpl_count first): the VPL count as the GPU knows it.
    const Buffer& counters() const { return counters_; }
    // The SmcVpl records of Y (tests: positions, anchors, radiosities).
    const Buffer& state() const { return state_; }

    SmcState(SmcState&&) = default;
    SmcState& operator=(SmcState&&) = default;

private:
    SmcState(const stages::SmcOptions& options, stages::KeyValueSorter sorter)
        : options_(options), sorter_(std::move(sorter)) {}
    stages::SmcBuffers views() const;

    stages::SmcOptions options_;
    stages::KeyValueSorter sorter_;
    uint32_t updates_ = 0;
    stages::SmcSceneChange change_;  // since the last update
    Buffer state_, valid_, invalid_list_, hits_, pool_keys_, pool_values_, candidates_, candidate_density_,
        vpl_density_, vpl_keys_, vpl_values_, candidate_keys_, candidate_values_, moves_, counters_, vpls_;
    Buffer triangle_slots_;  // made at the first move, for the scene's triangle count
};

}  // namespace vplkit
