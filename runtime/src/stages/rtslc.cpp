#include "vplkit/stages/rtslc.hpp"

#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/rtslc_cut.hpp"
#include "vplkit/shaders/rtslc_gi.hpp"
#include "vplkit/shaders/rtslc_interleave.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "gi_inputs.hpp"
#include "vplkit/stages/gi_counters.hpp"
#include "vplkit/stages/vpl_trees.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace vplkit::stages {

namespace {

[[noreturn]] void refuse(const std::string& what) { throw Error("rtslc: " + what); }

void check_targets(GbufferImages& gbuffer, const VplTrees& trees, Image& indirect, const Buffer& counters,
                   const RtslcOptions& options, const RtslcScratch& scratch) {
    check_gbuffer_target("rtslc", gbuffer, indirect);
    if (scratch.width != gbuffer.width() || scratch.height != gbuffer.height() ||
        scratch.block_size != options.block_size || scratch.cut_size != options.samples_per_pixel ||
        scratch.interleave != options.interleave) {
        refuse("the scratch was made for another image size or other samples_per_pixel, block_size or interleave");
    }
    if (trees.count == 0 || trees.leaf_count == 0) {
        refuse("the light tree holds no VPLs");
    }
    if (counters.size() < sizeof(shaders::GiCounters)) {
        refuse("buffer '" + counters.name() + "' is too small for the counters");
    }
}

}  // namespace

void validate(const RtslcOptions& options) {
    if (options.samples_per_pixel < 1 || options.samples_per_pixel > kRtslcMaxSamplesPerPixel) {
        refuse("samples_per_pixel " + std::to_string(options.samples_per_pixel) + " is not in 1.." +
               std::to_string(kRtslcMaxSamplesPerPixel));
    }
    if (options.block_size < 1 || options.block_size > kRtslcMaxBlockSize) {
        refuse("block_size " + std::to_string(options.block_size) + " is not in 1.." + std::to_string(kRtslcMaxBlockSize));
    }
    if (options.interleave < 1 || options.block_size % options.interleave != 0) {
        refuse("interleave " + std::to_string(options.interleave) + " does not divide block_size " +
               std::to_string(options.block_size));
    }
    // Fewer nodes than sub-block pixels would leave pixels without a share of a full cut.
    if (options.interleave * options.interleave > options.samples_per_pixel) {
        refuse("interleave " + std::to_string(options.interleave) + ": interleave^2 exceeds samples_per_pixel " +
               std::to_string(options.samples_per_pixel));
    }
    if (!std::isfinite(options.similarity_min_cos) || options.similarity_min_cos < -1.0f ||
        options.similarity_min_cos > 1.0f) {
        refuse("similarity_min_cos must be a finite cosine in [-1, 1]");
    }
    if (options.interleave > 1 &&
        !(std::isfinite(options.similarity_max_distance) && options.similarity_max_distance > 0.0f)) {
        refuse("similarity_max_distance must be finite and > 0 with interleave > 1 (an absolute distance: scale "
               "it to the scene)");
    }
    if (options.slots_per_dispatch < 1) {
        refuse("slots_per_dispatch must be at least 1");
    }
}

RtslcScratch RtslcScratch::create(Context& context, uint32_t width, uint32_t height, const RtslcOptions& options) {
    validate(options);
    if (width == 0 || height == 0) {
        refuse("a " + std::to_string(width) + " x " + std::to_string(height) + " image");
    }
    RtslcScratch scratch;
    scratch.width = width;
    scratch.height = height;
    scratch.block_size = options.block_size;
    scratch.cut_size = options.samples_per_pixel;
    scratch.interleave = options.interleave;
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    scratch.cuts = Buffer::create(context, VkDeviceSize(scratch.block_count()) * scratch.cut_size * sizeof(uint32_t),
                                  storage, MemoryUse::device, "rtslc cuts");
    scratch.representatives = Buffer::create(context, VkDeviceSize(scratch.block_count()) * sizeof(uint32_t), storage,
                                             MemoryUse::device, "rtslc representatives");
    if (options.interleave > 1) {
        scratch.estimates = Image::create(context, width, height, VK_FORMAT_R32G32B32A32_SFLOAT,
                                          VK_IMAGE_USAGE_STORAGE_BIT, "rtslc estimates");
    }
    return scratch;
}

void add_rtslc_passes(Context& context, PassList& passes, GbufferImages& gbuffer, const GpuBvh& bvh,
                      const VplTrees& trees, glm::vec3 camera_position, Image& indirect, Buffer& counters,
                      const RtslcOptions& options, RtslcScratch& scratch) {
    validate(options);
    check_targets(gbuffer, trees, indirect, counters, options, scratch);
    const shaders::vec3 camera{camera_position.x, camera_position.y, camera_position.z};
    add_gi_counters_clear(passes, counters, "gi counters clear");

    const auto& cut_pipeline = context.pipeline<shaders::rtslc_cut::Pipeline>();
    passes.add("rtslc cuts",
               gbuffer_bvh_uses(gbuffer, bvh,
                                {Use::read(trees.light_tree), Use::write(scratch.cuts), Use::write(scratch.representatives),
                                 Use::read_write(counters)}),
               [&cut_pipeline, &gbuffer, &bvh, &trees, &scratch, &counters, camera, options](VkCommandBuffer cmd) {
                   shaders::rtslc_cut::Bindings b;
                   bind_bvh(b, bvh);
                   bind_gbuffer(b, gbuffer);
                   b.light_tree = trees.light_tree.descriptor();
                   b.cuts = scratch.cuts.descriptor();
                   b.representatives = scratch.representatives.descriptor();
                   b.gi_counters = counters.descriptor();
                   shaders::rtslc_cut::Push push{};
                   push.camera_position = camera;
                   push.seed = options.seed;
                   push.frame = options.frame;
                   push.block_size = options.block_size;
                   push.cut_size = options.samples_per_pixel;
                   push.blocks_x = scratch.blocks_x();
                   push.blocks_y = scratch.blocks_y();
                   push.leaf_count = trees.leaf_count;
                   cut_pipeline.dispatch(cmd, b, push, scratch.block_count());
               });

    shaders::rtslc_gi::Spec spec;
    spec.kShadowRays = options.visibility ? 1u : 0u;
    const auto& gi_pipeline = context.pipeline<shaders::rtslc_gi::Pipeline>(spec);
    Image& radiance = options.interleave > 1 ? scratch.estimates : indirect;
    for (uint32_t first = 0; first < options.samples_per_pixel; first += options.slots_per_dispatch) {
        const uint32_t end = std::min(options.samples_per_pixel, first + options.slots_per_dispatch);
        passes.add("rtslc gi",
                   gbuffer_bvh_uses(gbuffer, bvh,
                                    {Use::read(trees.light_tree), Use::read(trees.leaves), Use::read(scratch.cuts),
                                     Use::read_write(counters), Use::read_write(radiance)}),
                   [&gi_pipeline, &gbuffer, &bvh, &trees, &scratch, &counters, &radiance, camera, options, first,
                    end](VkCommandBuffer cmd) {
                       shaders::rtslc_gi::Bindings b;
                       bind_bvh(b, bvh);
                       bind_gbuffer(b, gbuffer);
                       b.light_tree = trees.light_tree.descriptor();
                       b.leaves = trees.leaves.descriptor();
                       b.cuts = scratch.cuts.descriptor();
                       b.gi_counters = counters.descriptor();
                       b.radiance = radiance.descriptor();
                       shaders::rtslc_gi::Push push{};
                       push.camera_position = camera;
                       push.seed = options.seed;
                       push.frame = options.frame;
                       push.block_size = options.block_size;
                       push.cut_size = options.samples_per_pixel;
                       push.blocks_x = scratch.blocks_x();
                       push.leaf_count = trees.leaf_count;
                       push.interleave = options.interleave;
                       push.slot_first = first;
                       push.slot_end = end;
                       gi_pipeline.dispatch(cmd, b, push, radiance.width(), radiance.height());
                   });
    }

    if (options.interleave > 1) {
        const auto& interleave_pipeline = context.pipeline<shaders::rtslc_interleave::Pipeline>();
        passes.add("rtslc interleave",
                   {Use::read(gbuffer.position), Use::read(gbuffer.normal), Use::read(scratch.cuts),
                    Use::read(scratch.estimates), Use::write(indirect)},
                   [&interleave_pipeline, &gbuffer, &scratch, &indirect, options](VkCommandBuffer cmd) {
                       shaders::rtslc_interleave::Bindings b;
                       b.gbuffer_position = gbuffer.position.descriptor();
                       b.gbuffer_normal = gbuffer.normal.descriptor();
                       b.cuts = scratch.cuts.descriptor();
                       b.estimates = scratch.estimates.descriptor();
                       b.indirect = indirect.descriptor();
                       shaders::rtslc_interleave::Push push{};
                       push.block_size = options.block_size;
                       push.cut_size = options.samples_per_pixel;
                       push.blocks_x = scratch.blocks_x();
                       push.interleave = options.interleave;
                       push.frame = options.frame;
                       push.similarity_min_cos = options.similarity_min_cos;
                       push.similarity_max_distance = options.similarity_max_distance;
                       interleave_pipeline.dispatch(cmd, b, push, indirect.width(), indirect.height());
                   });
    }
}

}  // namespace vplkit::stages
