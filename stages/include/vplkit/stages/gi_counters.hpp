#pragma once
// The counters every sampling method (rtslc, sst, hybrid) increments while it renders indirect
// light (shaders/include/vplkit/gi_counters.glsl): dropped samples, traversals and the tree
// levels they descended, dead branches, mock cuts, and invocations a driver cut short.
// The buffer is the caller's (kGiCountersBytes, storage usage); the runtime's
// create_gi_counters / read_gi_counters (vplkit/gi_counters_buffer.hpp) allocate and read it.

#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <cstdint>

namespace vplkit::stages {

// The most samples per pixel (sst traversals, rtslc and hybrid cut nodes) any sampler takes:
// kGiMaxSamplesPerPixel in shaders/include/vplkit/gi_bounds.glsl, which sizes the cut arrays.
inline constexpr uint32_t kMaxGiSamplesPerPixel = 64;

// Bytes of the counters buffer: one GiCounters record (seven uint32; gi_counters.cpp checks it
// against the generated struct).
inline constexpr uint64_t kGiCountersBytes = 7 * sizeof(uint32_t);

struct GiCounts {
    uint32_t dropped_pixels = 0;   // pixels with at least one dropped (non-finite) sample
    uint32_t dropped_samples = 0;  // samples left out of their pixel because they were not finite
    uint32_t traversals = 0;       // tree traversals (one per sample)
    uint32_t levels = 0;           // tree levels descended, summed over the traversals
    uint32_t dead_branches = 0;    // traversals that ended where both children weigh 0
    uint32_t mock_cut_pixels = 0;  // hybrid: pixels with no similar block (the mock cut, or root traversals)
    uint32_t cut_short = 0;        // invocations the driver ended early: the image is wrong if > 0

    // Levels per traversal (the thesis Fig. 7.2); 0 without traversals.
    double levels_per_traversal() const { return traversals == 0 ? 0.0 : double(levels) / traversals; }
};

// Adds "<pass_name>": zeroes the kGiCountersBytes counters at the start of `counters` (written,
// transfer).
void add_gi_counters_clear(StepList& passes, const BufferView& counters, const char* pass_name);

}  // namespace vplkit::stages
