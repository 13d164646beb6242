#include "hazard_tracker.hpp"

#include "vplkit/steps.hpp"

namespace vplkit::detail {

BarrierNeed track_access(ResourceState& state, const ResourceAccess& access, bool is_image) {
    BarrierNeed need;
    const bool reads = access.read != 0;
    const bool writes = access.write != 0;
    const bool layout_change = is_image && access.layout != state.layout;

    if (writes) {
        if (state.written) {
            need.hazards |= hazard_write_after_write;
            need.src_stages |= state.write_stages;
            need.src_access |= state.write_access;
        }
        if (state.read_stages) {
            // Execution dependency only: reads leave nothing to make available.
            need.hazards |= hazard_write_after_read;
            need.src_stages |= state.read_stages;
        }
    }
    if (reads && state.written) {
        const bool visible = (access.stages & ~state.visible_stages) == 0 && (access.read & ~state.visible_access) == 0;
        if (!visible) {
            need.hazards |= hazard_read_after_write;
            need.src_stages |= state.write_stages;
            need.src_access |= state.write_access;
        }
    }
    if (layout_change) {
        // A layout transition reads and writes the whole image: after everything before it.
        need.hazards |= hazard_layout_transition;
        need.src_stages |= state.write_stages | state.read_stages;
        need.src_access |= state.write_access;
        need.old_layout = state.layout;
        need.new_layout = access.layout;
    }
    if (need.hazards) {
        need.dst_stages = access.stages;
        need.dst_access = access.read | access.write;
        if (!layout_change && is_image) need.old_layout = need.new_layout = state.layout;
    }

    if (writes || layout_change) {
        state.written = true;
        state.write_stages = access.stages;
        state.write_access = access.write;
        // A read in the transitioning pass is ordered after the transition by this very barrier.
        const bool read_only = reads && !writes;
        state.read_stages = read_only ? access.stages : 0;
        state.visible_stages = read_only ? access.stages : 0;
        state.visible_access = read_only ? access.read : 0;
    } else if (reads) {
        if (need.hazards & hazard_read_after_write) {
            state.visible_stages |= access.stages;
            state.visible_access |= access.read;
        }
        state.read_stages |= access.stages;
    }
    if (is_image) state.layout = access.layout;
    return need;
}

}  // namespace vplkit::detail
