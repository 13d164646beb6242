#ifndef VPLKIT_GI_COUNTERS_GLSL
#define VPLKIT_GI_COUNTERS_GLSL

// What a sampling method (rtslc, sst, hybrid) counts while it renders indirect light: the
// host reads these back and reports them (a dropped sample is counted, never silently
// zeroed; levels per traversal as in the thesis Fig. 7.2). Define VPLKIT_GI_COUNTERS_BINDING
// before including. Each invocation adds its pixel's totals once (one atomic per counter per
// pixel), so 32 bits last for 2^32 traversals: 1280 x 720 x 64 samples is 2^25.8.
layout(std430, set = 0, binding = VPLKIT_GI_COUNTERS_BINDING) buffer GiCounters {
    uint dropped_pixels;   // pixels with at least one dropped sample
    uint dropped_samples;  // samples whose contribution was not finite: left out of the pixel
    uint traversals;       // tree traversals started (one per sample)
    uint levels;           // tree levels descended, summed over the traversals
    uint dead_branches;    // traversals that ended where both children weigh 0 (no light)
    uint mock_cut_pixels;  // hybrid: pixels that used the mock cut (no similar block nearby)
    uint cut_short;        // invocations the driver stopped early (lavapipe's loop limit)
} gi_counters;

// Adds one pixel's counts.
void gi_counters_add(uint dropped, uint traversals, uint levels, uint dead, bool mock_cut, bool completed) {
    if (dropped > 0u) {
        atomicAdd(gi_counters.dropped_pixels, 1u);
        atomicAdd(gi_counters.dropped_samples, dropped);
    }
    if (traversals > 0u) {
        atomicAdd(gi_counters.traversals, traversals);
        atomicAdd(gi_counters.levels, levels);
    }
    if (dead > 0u) {
        atomicAdd(gi_counters.dead_branches, dead);
    }
    if (mock_cut) {
        atomicAdd(gi_counters.mock_cut_pixels, 1u);
    }
    if (!completed) {
        atomicAdd(gi_counters.cut_short, 1u);
    }
}

#endif
