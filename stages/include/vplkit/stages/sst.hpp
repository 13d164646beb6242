#pragma once
// Stochastic Substitute Tree build (shaders/tree/build_sst.comp; node layout and indexing in
// shaders/include/vplkit/sst.glsl): after the VPLs are gathered into sorted leaf order with bogus
// padding (leaves.hpp), one pass clears the per-node arrival counters and one dispatch builds
// every inner node bottom-up.
//
// Tree: heap order, root 0, children of i at 2i + 1 and 2i + 2; with L = leaf_count(count)
// leaves, nodes[0 .. L - 2] are the inner nodes and child index c >= L - 1 is leaf c - (L - 1)
// of the leaf buffer (leaves are not duplicated as nodes). For one VPL, nodes[0] is that leaf
// as a node, so nodes[0] always summarizes the whole tree.

#include "vplkit/stages/leaves.hpp"

#include "vplkit/stages/device.hpp"
#include "vplkit/steps.hpp"

#include <cstdint>

namespace vplkit::stages {

struct SstOptions {
    // Suitability thresholds (the SST paper eq. 3: nu >= nu_min and sigma_z <= sigma_max). Defaults are
    // the thesis' (the thesis sec. 5.2: 0.7 / 0.3); the SST paper used 0.5 / 0.1 (the SST paper sec. 6).
    // sigma_max is an absolute length in world units, as in both papers: sigma_z is the
    // standard deviation of the node's VPLs along its normal. A scene in other units (or far
    // larger or smaller than a room) needs it scaled accordingly: vplkit::Renderer does so by
    // default (RenderSettings::sigma_max_scene_fraction).
    float nu_min = 0.7f;
    float sigma_max = 0.3f;
    // Threads per workgroup of the build (a specialization constant).
    uint32_t workgroup_size = 256;
};

// SstNode records the node buffer holds for `count` VPLs: the L - 1 inner nodes, or 1 for a
// single VPL (the root record).
inline uint32_t sst_node_count(uint32_t count) {
    const uint32_t leaves = leaf_count(count);
    return leaves == 1 ? 1u : leaves - 1u;
}

// uint32_t arrival counters the build needs: one per inner node above the lowest inner level
// (indexed by node), at least 1 (Vulkan has no empty buffers).
inline uint32_t sst_counter_count(uint32_t count) {
    const uint32_t leaves = leaf_count(count);
    return leaves < 4 ? 1u : leaves / 2u - 1u;
}

// Adds two passes: "sst clear counters" (vkCmdFillBuffer) and "build sst".
// `leaves` holds leaf_count(count) Vpls in sorted order (index >= count: bogus, any data);
// `nodes` gets sst_node_count(count) SstNodes; `counters` holds sst_counter_count(count) uints
// (contents on entry do not matter); with a GPU count, every size is that of the capacity.
// Throws vplkit::Error for capacity 0, a buffer too small, thresholds that are not finite or a
// sigma_max < 0, or a workgroup size the device refuses.
void add_sst_passes(Device& device, StepList& passes, const BufferView& leaves, const BufferView& nodes,
                    const BufferView& counters, const ElementCount& count, const SstOptions& options = {});

}  // namespace vplkit::stages
