#pragma once
// Direct light through the light tree over the scene's lights (scene_light_tree.hpp), by real-time
// stochastic lightcuts (the RTSLC paper sec. 3.2-3.3) with rtslc GI's own cut and traversal code:
//
//   "gi counters clear"   zeroes `counters` (GiCounters, gi_counters.hpp)
//   "rtslc cuts"          shaders/gi/rtslc_cut.comp, the pass rtslc GI runs, over this tree: a cut
//                         of samples_per_pixel slots per block_size x block_size block, shared out
//                         by bound without interleaving (a leaf may fill several slots)
//   "direct light tree"   shaders/lighting/direct_light_tree.comp: per pixel, samples_per_pixel
//                         samples, slot s from the cut node in it (weighted 1 / its slots): a
//                         defensive traversal to a light (rtslc_traverse_defensive_in, pmf = the
//                         probability of the path), one area sample
//                         of a triangle (pdf 1 / area on it) or the point or spot light itself,
//                         one shadow ray; one dispatch per slots_per_dispatch slots
//
// Adds to `radiance` (RGBA32F, the G-buffer's size: the direct-light pass's output, which holds
// emission, background and the directional lights). Unbiased for the direct light of every
// light in the tree.
//
// Interleaved (RtslcOptions::interleave m > 1, the RTSLC paper sec. 3.4, as rtslc GI): each pixel of an
// m x m sub-block samples its share of the cut into scratch.estimates, then "rtslc interleave"
// (shaders/gi/rtslc_interleave.comp, rtslc GI's pass) writes every pixel the rescaled sum of its
// similar neighbours' shares: an approximation, biased at edges (that shader says why). That
// variant writes the tree's light alone into its own target (add_direct_light_tree_interleaved_passes);
// the caller adds it to the rest (the renderer composes the two).
//
// Two-level (the RTSLC paper sec. 3.1; a DirectLightTree holding TwoLevelLightTreeBuffers): the same passes
// with the cut in the top tree and a second traversal into the chosen mesh light's bottom tree
// (vplkit/two_level_light_tree.glsl; direct_light_tree.comp's kTwoLevel). The lights and the
// estimator are the same: only the tree the pmf comes from differs.

#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/stages/rtslc.hpp"
#include "vplkit/stages/scene_light_tree.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <glm/vec3.hpp>

#include <variant>

namespace vplkit::stages {

// A two-level tree as the sampling reads it (built by vplkit/two_level_light_tree.hpp).
struct TwoLevelLightTreeBuffers {
    uint32_t top_leaf_count = 0;  // the top tree's leaves, a power of two
    uint32_t triangle_count = 0;  // lights [0, triangle_count) are emitters, as SceneLightTreeBuffers
    BufferView nodes;             // LightTreeNode[]: the top tree, then every bottom tree
    BufferView bottoms;           // LightTreeBottom[top leaves]: where top leaf i's bottom tree is
    BufferView leaf_lights;       // uint32[]: bottom leaf j of top leaf i holds leaf_lights[light_base + j]
    BufferView emitters;          // as SceneLightTreeBuffers
    BufferView punctual;
};

// Throws vplkit::Error for bad options (rtslc's validate), naming "direct light tree".
void validate_direct_light_tree(const RtslcOptions& options);

// Either tree: one-level (scene_light_tree.hpp) or two-level. Both convert to it.
using DirectLightTree = std::variant<SceneLightTreeBuffers, TwoLevelLightTreeBuffers>;

// Adds the passes above (options.interleave must be 1). `scratch` as rtslc's
// (rtslc_scratch_requirements(width, height, options)). Read `counters` afterwards and distrust the image when
// cut_short > 0. Throws vplkit::Error for bad options, a tree without lights, a target of the wrong format or size, a
// scratch made for other options, or a counters buffer too small.
void add_direct_light_tree_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                                  const DirectLightTree& tree, glm::vec3 camera_position, const ImageView& radiance,
                                  const BufferView& counters, const RtslcOptions& options,
                                  const RtslcScratchBuffers& scratch);

// The interleaved variant: writes the tree's direct light alone (reconstructed) into `tree_light`
// (RGBA32F, storage, the G-buffer's size); needs options.interleave >= 2 and scratch.estimates.
void add_direct_light_tree_interleaved_passes(Device& device, StepList& passes, const GbufferViews& gbuffer,
                                              const BvhBuffers& bvh, const DirectLightTree& tree,
                                              glm::vec3 camera_position, const ImageView& tree_light,
                                              const BufferView& counters, const RtslcOptions& options,
                                              const RtslcScratchBuffers& scratch);

}  // namespace vplkit::stages
