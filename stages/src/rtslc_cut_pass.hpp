#pragma once
// The "rtslc cuts" pass (shaders/gi/rtslc_cut.comp) over any perfect light tree, and the "rtslc
// interleave" reconstruction (shaders/gi/rtslc_interleave.comp) of interleaved estimates: rtslc
// GI runs them over the VPLs' tree (rtslc.cpp), direct light over the scene lights' tree
// (direct_light_tree.cpp). Private to the stage sources.

#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/stages/rtslc.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <glm/vec3.hpp>

#include <cstdint>

namespace vplkit::stages {

// Adds the pass: one cut of options.samples_per_pixel nodes of `light_tree` (LightTreeNode[2
// leaf_count - 1]) per block into scratch.cuts and scratch.representatives, counting into
// `counters`. `seed` replaces options.seed (direct light salts its own). share_out_slots: the
// slots shared out by bound, a leaf possibly in several slots in a row (rtslc_cut.comp's
// kShareOutSlots; direct light without interleaving), else one slot per cut node (rtslc GI).
void add_rtslc_cut_pass(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                        const BufferView& light_tree, uint32_t leaf_count, glm::vec3 camera_position,
                        const BufferView& counters, const RtslcOptions& options, uint32_t seed,
                        const RtslcScratchBuffers& scratch, bool share_out_slots = false);

// The sampling pass's push constants both rtslc GI (rtslc_gi.comp) and direct light through the
// tree (direct_light_tree.comp) take alike: the camera, the random numbers, the cut's shape and
// the slots [first, end) this dispatch draws. Push is the shader's generated Push.
template <class Push>
void set_rtslc_sampling_push(Push& push, glm::vec3 camera_position, const RtslcOptions& options,
                             const RtslcScratchBuffers& scratch, uint32_t leaf_count, uint32_t first, uint32_t end) {
    push.camera_position = {camera_position.x, camera_position.y, camera_position.z};
    push.seed = options.seed;
    push.frame = options.frame;
    push.block_size = options.block_size;
    push.cut_size = options.samples_per_pixel;
    push.blocks_x = scratch.blocks_x();
    push.leaf_count = leaf_count;
    push.interleave = options.interleave;
    push.slot_first = first;
    push.slot_end = end;
}

// Adds the pass: each pixel of `target` gets the rescaled sum of its similar sub-block
// neighbours' estimates (scratch.estimates, written per pixel over its interleaved share of the
// cut). `similarity_distance` absolute (world units).
void add_rtslc_interleave_pass(Device& device, StepList& passes, const GbufferViews& gbuffer,
                               const RtslcScratchBuffers& scratch, const ImageView& target, const RtslcOptions& options,
                               float similarity_distance);

}  // namespace vplkit::stages
