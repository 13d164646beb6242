#include "vplkit/smc_state.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace vplkit {

namespace {

Buffer storage(Context& context, uint64_t bytes, const char* name) {
    return Buffer::create(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, name);
}

}  // namespace

SmcState SmcState::create(Context& context, const stages::SmcOptions& options) {
    stages::validate(options);
    const stages::SmcRequirements r = smc_requirements(options);
    stages::SortOptions sort;
    sort.key_bits = 32;  // the keys are float bits or kSmcNoKey
    SmcState s(options, stages::KeyValueSorter(context, r.pool, sort));
    s.state_ = storage(context, r.state_bytes, "smc state");
    s.valid_ = storage(context, r.word_bytes, "smc valid");
    s.invalid_list_ = storage(context, r.word_bytes, "smc invalid list");
    s.hits_ = storage(context, r.hit_bytes, "smc hits");
    s.pool_keys_ = storage(context, r.pool_key_bytes, "smc pool keys");
    s.pool_values_ = storage(context, r.pool_value_bytes, "smc pool values");
    s.candidates_ = storage(context, r.state_bytes, "smc candidates");
    s.candidate_density_ = storage(context, r.density_bytes, "smc candidate density");
    s.vpl_density_ = storage(context, r.density_bytes, "smc vpl density");
    s.vpl_keys_ = storage(context, r.key_bytes, "smc vpl keys");
    s.vpl_values_ = storage(context, r.word_bytes, "smc vpl values");
    s.candidate_keys_ = storage(context, r.key_bytes, "smc candidate keys");
    s.candidate_values_ = storage(context, r.word_bytes, "smc candidate values");
    s.moves_ = storage(context, r.move_bytes, "smc moves");
    s.counters_ = storage(context, r.counter_bytes, "smc counters");
    s.vpls_ = storage(context, r.vpl_bytes, "smc vpls");
    // Y starts empty: |Y| = 0 (the rest of the counters is cleared by every update).
    s.counters_.upload(std::vector<uint8_t>(r.counter_bytes, 0));
    return s;
}

stages::SmcBuffers SmcState::views() const {
    return {state_,       valid_,          invalid_list_,      hits_,        pool_keys_,
            pool_values_, candidates_,     candidate_density_, vpl_density_, vpl_keys_,
            vpl_values_,  candidate_keys_, candidate_values_,  moves_,       counters_,
            vpls_,        triangle_slots_};
}

void SmcState::add_update(Context& context, StepList& passes, const stages::GbufferViews& gbuffer,
                          const stages::CameraView& view, const stages::SmcScene& scene) {
    // Where each scene triangle lies in the BVH, for the VPLs to follow their surfaces.
    const uint64_t slot_bytes = uint64_t(std::max(scene.sources.triangle_count, 1u)) * sizeof(uint32_t);
    if (change_.geometry && (!triangle_slots_ || triangle_slots_.size() < slot_bytes)) {
        triangle_slots_ = storage(context, slot_bytes, "smc triangle slots");
    }
    add_smc_update_passes(context, passes, gbuffer, view, scene, sorter_, views(), options_, updates_, change_);
    change_ = {};
    ++updates_;
}

SmcCounts SmcState::read_counts() const {
    const auto c = counters_.download<shaders::SmcCounters>(1)[0];
    SmcCounts n;
    n.vpls = c.vpl_count;
    n.hits = c.hit_count;
    n.invalid = c.invalid_count;
    n.revalidated = c.revalidated;
    n.candidates = c.candidate_count;
    n.strong = c.strong_count;
    n.min_moves = c.min_moves;
    n.still_invalid = c.still_invalid;
    n.removed = c.removed;
    n.moved = c.move_count;
    n.cut_short = c.cut_short;
    if (n.cut_short > 0) {
        throw Error("smc: the driver ended " + std::to_string(n.cut_short) +
                    " radiosity estimates early (a loop iteration limit): use fewer radiosity samples or bounces");
    }
    return n;
}

}  // namespace vplkit
