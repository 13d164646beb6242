#include "vplkit/stages/direct_light_tree.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/direct_light_tree.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/gi_counters.hpp"
#include "vplkit/stages/gi_similarity.hpp"

#include "gi_inputs.hpp"
#include "rtslc_cut_pass.hpp"

#include <algorithm>
#include <string>
#include <variant>

namespace vplkit::stages {

namespace {

[[noreturn]] void refuse(const std::string& what) {
    throw Error("direct light tree: " + what);
}

// shaders/lighting/direct_light_tree.comp's salt, applied to the cut pass's seed too, so that
// direct light and rtslc GI with one seed draw independent numbers.
constexpr uint32_t kDirectTreeSalt = 0x85EBCA6Bu;

}  // namespace

void validate_direct_light_tree(const RtslcOptions& options) {
    try {
        validate(options);
    } catch (const Error& e) {
        refuse(e.what());
    }
}

namespace {

// Either tree as the passes read it: one-level is a two-level tree without bottoms.
struct TreeView {
    uint32_t leaf_count = 0;  // the (top) tree's leaves: the cut's and the first traversal's
    uint32_t triangle_count = 0;
    bool two_level = false;
    BufferView nodes, bottoms, leaf_lights, emitters, punctual;
};

TreeView view_of(const SceneLightTreeBuffers& tree) {
    if (tree.count == 0 || tree.leaf_count == 0) refuse("the tree holds no lights");
    // One-level, the shader does not read `bottoms`; the binding still needs a buffer.
    return {tree.leaf_count,  tree.triangle_count, false,         tree.nodes,
            tree.leaf_lights, tree.leaf_lights,    tree.emitters, tree.punctual};
}

TreeView view_of(const TwoLevelLightTreeBuffers& tree) {
    if (tree.top_leaf_count == 0) refuse("the two-level tree holds no lights");
    return {tree.top_leaf_count, tree.triangle_count, true,          tree.nodes,
            tree.bottoms,        tree.leaf_lights,    tree.emitters, tree.punctual};
}

// The passes of both entry points: sampling into `radiance` (added) or, interleaved, into the
// scratch's estimates and then the reconstruction into `radiance` (written).
void add_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                const TreeView& tree, glm::vec3 camera_position, const ImageView& radiance, const BufferView& counters,
                const RtslcOptions& options, const RtslcScratchBuffers& scratch) {
    validate_direct_light_tree(options);
    check_gbuffer_target("direct light tree", gbuffer, radiance);
    if (scratch.width != gbuffer.width() || scratch.height != gbuffer.height() ||
        scratch.block_size != options.block_size || scratch.cut_size != options.samples_per_pixel ||
        scratch.interleave != options.interleave) {
        refuse("the scratch was made for another image size or other samples_per_pixel, block_size or interleave");
    }
    const RtslcScratchRequirements needs = rtslc_scratch_requirements(scratch.width, scratch.height, options);
    if (scratch.cuts.size < needs.cuts_bytes || scratch.representatives.size < needs.representatives_bytes) {
        refuse("the scratch's buffers are smaller than rtslc_scratch_requirements");
    }
    if (needs.estimates && (scratch.estimates.format != VK_FORMAT_R32G32B32A32_SFLOAT ||
                            scratch.estimates.width != scratch.width || scratch.estimates.height != scratch.height)) {
        refuse("the scratch's estimates '" + scratch.estimates.name + "' must be RGBA32F and of the G-buffer's size");
    }
    if (counters.size < kGiCountersBytes) refuse("buffer '" + counters.name + "' is too small for the counters");

    add_gi_counters_clear(passes, counters, "gi counters clear");
    add_rtslc_cut_pass(device, passes, gbuffer, bvh, tree.nodes, tree.leaf_count, camera_position, counters, options,
                       options.seed ^ kDirectTreeSalt, scratch, options.interleave <= 1);

    shaders::direct_light_tree::Spec spec;
    spec.kShadowRays = options.visibility ? 1u : 0u;
    spec.kTwoLevel = tree.two_level ? 1u : 0u;
    const auto& pipeline = device.pipeline<shaders::direct_light_tree::Pipeline>(bvh_spec(bvh, spec));
    const ImageView samples_target = options.interleave > 1 ? scratch.estimates : radiance;
    shaders::direct_light_tree::Bindings b;
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({bvh.nodes, bvh.triangles, bvh.alpha, tree.nodes, tree.leaf_lights, tree.emitters, tree.punctual,
                  tree.bottoms, scratch.cuts, counters});
    bind_bvh(b, bvh);
    bind_gbuffer(b, gbuffer);
    b.light_tree = tree.nodes.descriptor();
    b.leaf_lights = tree.leaf_lights.descriptor();
    b.emitters = tree.emitters.descriptor();
    b.lights = tree.punctual.descriptor();
    b.bottoms = tree.bottoms.descriptor();
    b.cuts = scratch.cuts.descriptor();
    b.gi_counters = counters.descriptor();
    b.radiance = samples_target.descriptor();
    for (uint32_t first = 0; first < options.samples_per_pixel; first += options.slots_per_dispatch) {
        const uint32_t end = std::min(options.samples_per_pixel, first + options.slots_per_dispatch);
        shaders::direct_light_tree::Push push{};
        set_rtslc_sampling_push(push, camera_position, options, scratch, tree.leaf_count, first, end);
        push.triangle_count = tree.triangle_count;
        add_dispatch<shaders::direct_light_tree::Module>(passes, "direct light tree", pipeline, b, push,
                                                         {samples_target.width, samples_target.height},
                                                         gbuffer_images(gbuffer, {samples_target}));
    }
    if (options.interleave > 1) {
        add_rtslc_interleave_pass(device, passes, gbuffer, scratch, radiance, options,
                                  gi_similarity_distance(options.similarity_max_distance, bvh.scene_scale));
    }
}

}  // namespace

void add_direct_light_tree_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                                  const DirectLightTree& tree, glm::vec3 camera_position, const ImageView& radiance,
                                  const BufferView& counters, const RtslcOptions& options,
                                  const RtslcScratchBuffers& scratch) {
    if (options.interleave != 1) {
        refuse("interleaved sampling writes the tree's light alone: use add_direct_light_tree_interleaved_passes");
    }
    const TreeView view = std::visit([](const auto& t) { return view_of(t); }, tree);
    add_passes(device, passes, gbuffer, bvh, view, camera_position, radiance, counters, options, scratch);
}

void add_direct_light_tree_interleaved_passes(Device& device, StepList& passes, const GbufferViews& gbuffer,
                                              const BvhBuffers& bvh, const DirectLightTree& tree,
                                              glm::vec3 camera_position, const ImageView& tree_light,
                                              const BufferView& counters, const RtslcOptions& options,
                                              const RtslcScratchBuffers& scratch) {
    if (options.interleave < 2) refuse("interleaved passes need interleave >= 2");
    const TreeView view = std::visit([](const auto& t) { return view_of(t); }, tree);
    add_passes(device, passes, gbuffer, bvh, view, camera_position, tree_light, counters, options, scratch);
}

}  // namespace vplkit::stages
