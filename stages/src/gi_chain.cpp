#include "vplkit/stages/gi_chain.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/gi_counters.hpp"
#include "vplkit/stages/leaves.hpp"
#include "vplkit/stages/svgf.hpp"

#include <glm/matrix.hpp>

#include <cmath>
#include <map>
#include <string>

namespace vplkit::stages {

namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
// Buffers a stage clears with vkCmdFillBuffer before its shaders use them.
constexpr VkBufferUsageFlags kCleared = kStorage | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
constexpr VkFormat kRgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;

[[noreturn]] void refuse(const std::string& why) {
    throw Error("gi chain: " + why);
}

}  // namespace

GiChainRequirements gi_chain_requirements(const Limits& limits, const GiChainOptions& options) {
    if (options.width == 0 || options.height == 0) refuse("the image size must not be 0");
    const std::optional<float> fraction = options.sigma_max_scene_fraction;
    if (fraction && !(std::isfinite(*fraction) && *fraction >= 0.0f)) {
        refuse("sigma_max_scene_fraction must be finite and >= 0");
    }
    GiChainRequirements r;
    auto buffer = [&r](std::string name, uint64_t bytes, VkBufferUsageFlags usage = kStorage) {
        r.buffers.push_back({std::move(name), bytes, usage});
    };
    auto image = [&r, &options](std::string name, VkFormat format) {
        r.images.push_back({std::move(name), format, options.width, options.height, VK_IMAGE_USAGE_STORAGE_BIT});
    };

    // The VPLs and what orders them (vpl_tracing.hpp, vpl_keys.hpp, radix_sort.hpp, leaves.hpp).
    const VplTracingRequirements tracing = vpl_tracing_requirements(options.tracing);
    const uint32_t n = r.vpl_capacity = tracing.capacity;
    if (n > kMaxKeyedVpls) {
        refuse(std::to_string(n) + " VPLs a frame (paths x max_bounces) exceed the " + std::to_string(kMaxKeyedVpls) +
               " the sort keys can tell apart");
    }
    buffer("vpls", tracing.vpls_bytes);
    buffer("vpl bounces", tracing.bounces_bytes);
    buffer("vpl count", tracing.count_bytes, kCleared);
    buffer("path vpls", tracing.path_vpls_bytes);
    buffer("path counts", tracing.path_counts_bytes);
    buffer("block vpls", tracing.block_vpls_bytes);
    buffer("vpl bounds", kVplBoundsBytes, kCleared);
    buffer("vpl keys", uint64_t(n) * sizeof(uint64_t));
    buffer("vpl key values", uint64_t(n) * sizeof(uint32_t));
    const RadixSortRequirements sort = radix_sort_requirements(limits, n, options.sort);
    buffer("sort keys", sort.key_bytes);
    buffer("sort values", sort.value_bytes);
    buffer("sort counts", sort.count_bytes);
    buffer("leaves", uint64_t(leaf_count(n)) * sizeof(shaders::Vpl));
    buffer("gi counters", kGiCountersBytes, kCleared);

    // The method's tree and scratch: each method reads its own tree only.
    if (options.method == GiChainMethod::hybrid) {
        buffer("sst", uint64_t(sst_node_count(n)) * sizeof(shaders::SstNode));
        buffer("sst counters", uint64_t(sst_counter_count(n)) * sizeof(uint32_t), kCleared);
        const HybridCutRequirements cuts = hybrid_cut_requirements(options.width, options.height, options.hybrid);
        buffer("hybrid cut blocks", cuts.blocks_bytes);
        buffer("hybrid cuts", cuts.cuts_bytes);
    } else {
        buffer("light tree", uint64_t(light_tree_node_count(n)) * sizeof(shaders::LightTreeNode));
        const RtslcScratchRequirements scratch =
            rtslc_scratch_requirements(options.width, options.height, options.rtslc);
        buffer("rtslc cuts", scratch.cuts_bytes);
        buffer("rtslc representatives", scratch.representatives_bytes);
        if (scratch.estimates) image("rtslc estimates", kRgba32f);
    }

    // The kit's G-buffer (written by the adapter), the indirect light, and SVGF's images.
    image("gbuffer position", kGbufferPositionFormat);
    image("gbuffer normal", kGbufferNormalFormat);
    image("gbuffer geometric normal", kGbufferGeometricNormalFormat);
    image("gbuffer albedo", kGbufferAlbedoFormat);
    image("indirect", kRgba32f);
    if (options.denoise) {
        validate(options.denoise_options);
        for (uint32_t i = 0; i < kSvgfImageCount; ++i) image("svgf " + std::to_string(i), kRgba32f);
    }
    return r;
}

GiChain::GiChain(Device& device, const GiChainOptions& options, const AllocateBuffer& allocate_buffer,
                 const AllocateImage& allocate_image)
    : device_(&device), options_(options), requirements_(gi_chain_requirements(device.limits(), options)) {
    std::map<std::string, BufferView> buffers;
    for (const BufferRequirement& need : requirements_.buffers) {
        BufferView view = allocate_buffer(need);
        if (!view || view.size < need.bytes) {
            refuse("the buffer for '" + need.name + "' holds " + std::to_string(view ? view.size : 0) +
                   " bytes, the chain needs " + std::to_string(need.bytes));
        }
        if (view.name.empty()) view.name = need.name;
        buffers[need.name] = view;
    }
    std::map<std::string, ImageView> images;
    for (const ImageRequirement& need : requirements_.images) {
        ImageView view = allocate_image(need);
        if (!view || view.format != need.format || view.width != need.width || view.height != need.height) {
            refuse("the image for '" + need.name + "' is not of the format and size its requirement names");
        }
        if (view.name.empty()) view.name = need.name;
        if (!view.layout) {  // the chain tracks it, so the caller need not transition it first
            image_layouts_.push_back(VK_IMAGE_LAYOUT_UNDEFINED);
            view.layout = &image_layouts_.back();
        }
        images[need.name] = view;
    }
    auto buffer = [&buffers](const char* name) { return buffers.count(name) ? buffers.at(name) : BufferView{}; };
    auto image = [&images](const std::string& name) { return images.count(name) ? images.at(name) : ImageView{}; };

    tracing_ = {buffer("vpls"),      buffer("vpl bounces"), buffer("vpl count"),
                buffer("path vpls"), buffer("path counts"), buffer("block vpls")};
    keys_ = {tracing_.vpls, buffer("vpl bounds"), buffer("vpl keys"), buffer("vpl key values")};
    const uint32_t n = requirements_.vpl_capacity;
    sorter_ = std::make_unique<RadixSorter>(
        device, n, RadixSortScratch{buffer("sort keys"), buffer("sort values"), buffer("sort counts")}, options.sort);
    // The trees over the capacity: the GPU's count is read when the passes run.
    trees_ = {n, leaf_count(n), buffer("leaves"), buffer("light tree"), buffer("sst")};
    sst_counters_ = buffer("sst counters");
    gi_counters_ = buffer("gi counters");
    const uint32_t w = options.width, h = options.height;
    if (options.method == GiChainMethod::hybrid) {
        const HybridCutRequirements cuts = hybrid_cut_requirements(w, h, options.hybrid);
        hybrid_cuts_ = {cuts.blocks_x, cuts.blocks_y, cuts.cut_size, buffer("hybrid cut blocks"),
                        buffer("hybrid cuts")};
    } else {
        const RtslcOptions& r = options.rtslc;
        rtslc_scratch_ = {w,
                          h,
                          r.block_size,
                          r.samples_per_pixel,
                          r.interleave,
                          buffer("rtslc cuts"),
                          buffer("rtslc representatives"),
                          image("rtslc estimates")};
    }
    gbuffer_.position = image("gbuffer position");
    gbuffer_.normal = image("gbuffer normal");
    gbuffer_.geometric_normal = image("gbuffer geometric normal");
    gbuffer_.albedo = image("gbuffer albedo");
    indirect_ = image("indirect");
    if (options.denoise) {
        for (uint32_t i = 0; i < kSvgfImageCount; ++i) svgf_.push_back(image("svgf " + std::to_string(i)));
    }
}

void GiChain::add_gi_passes(StepList& steps, const GiChainInputs& inputs, const GiChainFrame& frame) {
    Device& device = *device_;
    scene_scale_ = inputs.bvh.scene_scale;
    VplTracingOptions tracing = options_.tracing;
    tracing.seed += frame.index;  // other VPLs every frame
    add_trace_vpls_passes(device, steps, inputs.bvh, inputs.sources, tracing, tracing_);
    // The count the tracer wrote, read on the GPU: everything after is sized by the capacity.
    const ElementCount count = ElementCount::on_gpu(tracing_.count, 0, trees_.count);
    add_vpl_key_passes(device, steps, keys_, count);
    sorter_->add_pass(steps, keys_.keys, keys_.values, trees_.count);  // the padding sorts last
    add_gather_leaves_pass(device, steps, tracing_.vpls, keys_.values, trees_.leaves, count);

    GbufferAdapterOptions adapter = options_.adapter;
    adapter.inverse_view_projection = glm::inverse(frame.view_projection);
    adapter.view_to_world = frame.view_to_world;
    if (options_.method == GiChainMethod::hybrid) {
        SstOptions sst = options_.sst;
        if (options_.sigma_max_scene_fraction) sst.sigma_max = *options_.sigma_max_scene_fraction * scene_scale_;
        add_sst_passes(device, steps, trees_.leaves, trees_.sst, sst_counters_, count, sst);
        add_gbuffer_adapter_pass(device, steps, inputs.gbuffer, adapter, gbuffer_);
        HybridOptions hybrid = options_.hybrid;
        hybrid.frame = frame.index;
        add_hybrid_gi_passes(device, steps, gbuffer_, inputs.bvh, trees_, frame.camera_position, indirect_,
                             gi_counters_, hybrid_cuts_, hybrid);
    } else {
        add_light_tree_passes(device, steps, trees_.leaves, trees_.light_tree, count, options_.light_tree);
        add_gbuffer_adapter_pass(device, steps, inputs.gbuffer, adapter, gbuffer_);
        RtslcOptions rtslc = options_.rtslc;
        rtslc.frame = frame.index;
        add_rtslc_passes(device, steps, gbuffer_, inputs.bvh, trees_, frame.camera_position, indirect_, gi_counters_,
                         rtslc, rtslc_scratch_);
    }
}

void GiChain::add_denoise_passes(StepList& steps, const GiChainFrame& frame) {
    if (!options_.denoise)
        refuse("denoising is off in its options (GiChainOptions::denoise), so it has no SVGF images");
    DenoiseOptions denoise = options_.denoise_options;
    denoise.scene_scale = scene_scale_;  // SVGF's lengths are shares of it
    add_svgf_passes(*device_, steps, gbuffer_, indirect_, svgf_,
                    {frame.index, frame.view_projection, previous_view_projection_}, denoise);
    previous_view_projection_ = frame.view_projection;  // what the next frame reprojects with
}

}  // namespace vplkit::stages
