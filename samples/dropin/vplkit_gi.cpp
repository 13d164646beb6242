#include "vplkit_gi.hpp"

#include "vplkit/bvh.hpp"
#include "vplkit/stages/compose.hpp"
#include "vplkit/stages/gbuffer_adapter.hpp"
#include "vplkit/stages/leaves.hpp"
#include "vplkit/stages/renderer_vpl_sources.hpp"
#include "vplkit/stages/svgf.hpp"

#include <glm/matrix.hpp>

#include <algorithm>
#include <cstring>

namespace dropin {

namespace vs = vplkit::stages;

namespace {

constexpr vs::VplTracingOptions kTracing{/*paths=*/1024, /*max_bounces=*/2, /*seed=*/0};  // seed: the frame

vplkit::ImageView view(const GpuImage& i, const char* name) {
    return {i.image, i.view, i.format, i.width, i.height, name, i.aspect};  // no layout pointer: layouts are ours
}

}  // namespace

IndirectLight::IndirectLight(const Gpu& gpu, const Scene& scene, const Rasterizer& targets)
    : gpu_(&gpu), targets_(&targets), kit_(std::make_unique<vs::Device>(gpu.physical_device, gpu.device)) {
    auto buffer = [&](uint64_t bytes, const char* name, const void* data = nullptr) {
        buffers_.push_back(HostBuffer::create(gpu, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT));
        if (data) std::memcpy(buffers_.back().mapped, data, bytes);
        return vplkit::BufferView{buffers_.back().buffer, 0, bytes, name};
    };
    // The scene as the kit reads it: the triangles (3 vertices each), an albedo per triangle, and
    // the light in the kit's units (the renderer shades albedo * N.L: x pi).
    std::vector<glm::vec3> triangles, albedo;
    for (size_t i = 0; i < scene.vertices.size(); ++i) {
        triangles.push_back(scene.vertices[i].position);
        if (i % 3 == 0) albedo.push_back(scene.vertices[i].albedo);
    }
    vs::RendererLight light;
    light.position = scene.light_position;
    light.intensity = vs::radiometric_from_albedo_ndotl(scene.light_color);
    const vs::VplSourceData sources = vs::vpl_sources_from_renderer({&light, 1}, {}, {triangles, albedo});
    std::vector<uint8_t> source_bytes(sources.bytes());
    sources.write(source_bytes.data());
    sources_ = sources.views(buffer(source_bytes.size(), "vpl sources", source_bytes.data()));
    const vplkit::Bvh bvh = vplkit::build_bvh(triangles);
    const uint32_t no_alpha_test = 0;
    bvh_ = {buffer(bvh.nodes.size() * sizeof(bvh.nodes[0]), "bvh nodes", bvh.nodes.data()),
            buffer(bvh.triangles.size() * sizeof(bvh.triangles[0]), "bvh triangles", bvh.triangles.data()),
            uint32_t(bvh.nodes.size()),
            uint32_t(bvh.triangles.size()),
            bvh.scene_scale,
            buffer(4, "bvh alpha", &no_alpha_test),
            /*alpha_tests=*/false};

    // The VPLs' buffers and the trees', sized for the most VPLs a frame can trace.
    const vs::VplTracingRequirements t = vs::vpl_tracing_requirements(kTracing);
    tracing_ = {buffer(t.vpls_bytes, "vpls"),
                buffer(t.bounces_bytes, "vpl bounces"),
                buffer(t.count_bytes, "vpl count"),
                buffer(t.path_vpls_bytes, "path vpls"),
                buffer(t.path_counts_bytes, "path counts"),
                buffer(t.block_vpls_bytes, "block vpls")};
    const uint32_t n = t.capacity;
    keys_ = {tracing_.vpls, buffer(vs::kVplBoundsBytes, "vpl bounds"), buffer(n * 8ull, "keys"),
             buffer(n * 4ull, "values")};
    const vs::RadixSortRequirements sort = vs::radix_sort_requirements(kit_->limits(), n);
    sorter_ = std::make_unique<vs::RadixSorter>(
        *kit_, n,
        vs::RadixSortScratch{buffer(sort.key_bytes, "sort keys"), buffer(sort.value_bytes, "sort values"),
                             buffer(sort.count_bytes, "sort counts")});
    trees_ = {n,
              vs::leaf_count(n),
              buffer(vs::leaf_count(n) * sizeof(vplkit::shaders::Vpl), "leaves"),
              {},
              buffer(vs::sst_node_count(n) * sizeof(vplkit::shaders::SstNode), "sst")};
    trees_.light_tree = trees_.sst;  // hybrid reads only the leaves and the SST
    sst_counters_ = buffer(vs::sst_counter_count(n) * 4ull, "sst counters");
    gi_counters_ = buffer(vs::kGiCountersBytes, "gi counters");
    sst_.sigma_max = 0.012f * bvh.scene_scale;  // an absolute length: scaled to the scene as the runtime does
    hybrid_.samples_per_pixel = 16;
    const uint32_t w = targets.colour.width, h = targets.colour.height;
    const vs::HybridCutRequirements cuts = vs::hybrid_cut_requirements(w, h, hybrid_);
    cuts_ = {cuts.blocks_x, cuts.blocks_y, cuts.cut_size, buffer(cuts.blocks_bytes, "cut blocks"),
             buffer(cuts.cuts_bytes, "cuts")};
    denoise_.scene_scale = bvh.scene_scale;

    // The kit's images: its G-buffer, the indirect light and the denoiser's, GENERAL throughout.
    auto image = [&](VkFormat format, const char* name) {
        images_.push_back(GpuImage::create(gpu, w, h, format, VK_IMAGE_USAGE_STORAGE_BIT));
        return view(images_.back(), name);
    };
    const VkFormat rgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;
    gbuffer_.position = image(vs::kGbufferPositionFormat, "position");
    gbuffer_.normal = image(vs::kGbufferNormalFormat, "normal");
    gbuffer_.geometric_normal = image(vs::kGbufferGeometricNormalFormat, "geometric normal");
    gbuffer_.albedo = image(vs::kGbufferAlbedoFormat, "gbuffer albedo");
    indirect_image_ = images_.size();
    indirect_ = image(rgba32f, "indirect");
    for (vplkit::ImageView& i : svgf_) i = image(rgba32f, "svgf");
    gpu.submit([&](VkCommandBuffer cmd) {
        for (const GpuImage& i : images_) transition(cmd, i, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    });
}

void IndirectLight::record_gi(VkCommandBuffer cmd, const Camera& camera, uint32_t frame) {
    vplkit::StepList steps;
    vs::VplTracingOptions tracing = kTracing;
    tracing.seed = frame;  // new VPLs every frame
    vs::add_trace_vpls_pass(*kit_, steps, bvh_, sources_, tracing, tracing_);
    // The count the tracer wrote, read on the GPU: the trees are sized by the capacity.
    const vs::ElementCount count = vs::ElementCount::on_gpu(tracing_.count, 0, trees_.count);
    vs::add_vpl_key_passes(*kit_, steps, keys_, count);
    sorter_->add_pass(steps, keys_.keys, keys_.values, trees_.count);  // the padding sorts last
    vs::add_gather_leaves_pass(*kit_, steps, tracing_.vpls, keys_.values, trees_.leaves, count);
    vs::add_sst_passes(*kit_, steps, trees_.leaves, trees_.sst, sst_counters_, count, sst_);

    // The renderer's depth, octahedral world normal and albedo as the kit's G-buffer.
    vs::GbufferAdapterOptions adapter;
    adapter.inverse_view_projection = glm::inverse(camera.view_projection);
    adapter.normal_encoding = vs::GbufferNormalEncoding::octahedral;
    adapter.roughness = -1.0f;  // the renderer's surfaces are Lambertian
    const Rasterizer& r = *targets_;
    vs::add_gbuffer_adapter_pass(*kit_, steps,
                                 {view(r.depth, "depth"), view(r.normal, "normal"), view(r.albedo, "albedo"), {}},
                                 adapter, gbuffer_);
    hybrid_.seed = hybrid_.frame = frame;
    vs::add_hybrid_gi_passes(*kit_, steps, gbuffer_, bvh_, trees_, camera.eye, indirect_, gi_counters_, cuts_, hybrid_);
    record(cmd, steps);
}

void IndirectLight::record_denoise_and_compose(VkCommandBuffer cmd, const Camera& camera, uint32_t frame) {
    vplkit::StepList steps;
    vs::add_svgf_passes(*kit_, steps, gbuffer_, indirect_, svgf_, {frame, camera.view_projection, previous_}, denoise_);
    previous_ = camera.view_projection;  // what the next frame reprojects the history with
    const Rasterizer& r = *targets_;
    vs::add_compose_pass(*kit_, steps, view(r.colour, "colour"), indirect_, view(r.output, "output"));
    record(cmd, steps);
}

void IndirectLight::record(VkCommandBuffer cmd, const vplkit::StepList& steps) {
    full_barrier(cmd);  // the renderer's writes before the kit's steps...
    steps.record(cmd);  // (barriers between the kit's own steps are the kit's)
    full_barrier(cmd);  // ...and the kit's before the renderer's next commands
}

std::vector<vplkit::shaders::Vpl> IndirectLight::traced_vpls() const {
    auto mapped = [&](const vplkit::BufferView& v) {
        for (const HostBuffer& b : buffers_) {
            if (b.buffer == v.buffer) return b.mapped;
        }
        return static_cast<void*>(nullptr);
    };
    const uint32_t count = std::min(*static_cast<const uint32_t*>(mapped(tracing_.count)), trees_.count);
    const auto* first = static_cast<const vplkit::shaders::Vpl*>(mapped(tracing_.vpls));
    return {first, first + count};
}

void IndirectLight::destroy() {
    for (HostBuffer& b : buffers_) b.destroy(*gpu_);
    for (GpuImage& i : images_) i.destroy(*gpu_);
    kit_->destroy_pipelines();
}

}  // namespace dropin
