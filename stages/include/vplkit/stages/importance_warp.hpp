#pragma once
// Sampling core of BRSM VPL generation (the thesis sec. 4.1, ch. 6): a mip chain of a square
// power-of-two importance map (importance_mips.comp) and the hierarchical warp of a randomized
// Hammersley point set into its texels (warp_samples.comp, shaders/include/vplkit/sampling.glsl).
//
// Mip buffer layout (float[importance_mip_floats(size)]): all levels, finest first, each row-major;
// level k is (size >> k)^2 floats and each texel is the SUM of the 2x2 below, so the last float
// (importance_top_offset(size)) is the total importance.
// Samples (shaders::WarpedSample[sample_count]): texel = y * size + x, pmf = importance / total.
// Count (shaders::WarpCountBuffer): sample_count, or 0 when the total importance is not positive
// (an all-zero map), in which case no sample is written.
// The map must be finite and non-negative (it is an importance): a negative texel breaks the ratios.

#include "vplkit/stages/device.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <cstdint>

namespace vplkit::stages {

// Floats of the whole chain for a size x size map, and the index of the 1x1 level in it.
// Throw vplkit::Error unless size is a power of two in 1..4096.
uint64_t importance_mip_floats(uint32_t size);
uint64_t importance_top_offset(uint32_t size);

// Adds "importance copy" (the map, size x size floats read from `importance`, into level 0 of
// `mips`) and one pass "importance mips" per coarser level (`mips` read and written). Throws
// vplkit::Error for a bad size or buffers too small.
void add_importance_mips_passes(Device& device, StepList& passes, const BufferView& importance, const BufferView& mips,
                                uint32_t size);

// The same chain for a map already in level 0 of `mips` (a stage wrote it there): one pass
// "importance mips" per coarser level, none for size 1.
void add_importance_mip_levels_passes(Device& device, StepList& passes, const BufferView& mips, uint32_t size);

// Adds "warp samples": sample_count points of the Hammersley set rotated by `seed`, warped down
// `mips` (read; built by add_importance_mips_passes for the same size) into `samples` and `count`
// (both written). Throws vplkit::Error for a bad size, sample_count 0 or buffers too small.
void add_warp_samples_pass(Device& device, StepList& passes, const BufferView& mips, const BufferView& samples,
                           const BufferView& count, uint32_t size, uint32_t sample_count, uint32_t seed);

}  // namespace vplkit::stages
