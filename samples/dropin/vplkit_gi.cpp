#include "vplkit_gi.hpp"

#include "vplkit/bvh.hpp"
#include "vplkit/stages/compose.hpp"
#include "vplkit/stages/renderer_vpl_sources.hpp"

#include <algorithm>
#include <cstring>
#include <string>

namespace dropin {

namespace vs = vplkit::stages;

namespace {

vplkit::ImageView view(const GpuImage& i, const std::string& name) {
    return {i.image, i.view, i.format, i.width, i.height, name, i.aspect};  // no layout pointer: layouts are ours
}

// One barrier per resource the kit's steps touch: on the kit's side the step's own stages,
// access and layout (entry(): its first use, exit(): its last); on the renderer's side all its
// commands. Images stay in the layout the kit uses: the renderer leaves them so (renderer.hpp).
void barriers(VkCommandBuffer cmd, const std::vector<vplkit::ResourceUse>& uses, bool before_kit) {
    const VkPipelineStageFlags2 ours = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    std::vector<VkBufferMemoryBarrier2> buffers;
    std::vector<VkImageMemoryBarrier2> images;
    for (const vplkit::ResourceUse& u : uses) {
        const VkPipelineStageFlags2 src = before_kit ? ours : u.stages, dst = before_kit ? u.stages : ours;
        const VkAccessFlags2 src_access = before_kit ? VK_ACCESS_2_MEMORY_WRITE_BIT : u.access_flags;
        const VkAccessFlags2 dst_access =
            before_kit ? u.access_flags : VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
        if (u.buffer) {
            buffers.push_back({VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2, nullptr, src, src_access, dst, dst_access, 0,
                               0, u.buffer, 0, VK_WHOLE_SIZE});  // equal queue families: no ownership transfer
        } else {
            const VkImageSubresourceRange all{u.name == "depth" ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT,
                                              0, 1, 0, 1};
            images.push_back({VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, nullptr, src, src_access, dst, dst_access,
                              u.layout, u.layout, 0, 0, u.image, all});
        }
    }
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.bufferMemoryBarrierCount = uint32_t(buffers.size());
    dependency.pBufferMemoryBarriers = buffers.data();
    dependency.imageMemoryBarrierCount = uint32_t(images.size());
    dependency.pImageMemoryBarriers = images.data();
    vkCmdPipelineBarrier2(cmd, &dependency);
}

void* mapped(const std::vector<HostBuffer>& buffers, const vplkit::BufferView& v) {
    return std::find_if(buffers.begin(), buffers.end(), [&](const HostBuffer& h) { return h.buffer == v.buffer; })
        ->mapped;
}

}  // namespace

IndirectLight::IndirectLight(const Gpu& gpu, const Scene& scene, const Rasterizer& targets)
    : gpu_(&gpu), targets_(&targets), kit_(std::make_unique<vs::Device>(gpu.physical_device, gpu.device)) {
    auto buffer = [&](uint64_t bytes, const std::string& name, const void* data = nullptr,
                      VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
        buffers_.push_back(HostBuffer::create(gpu, bytes, usage));
        if (data) std::memcpy(buffers_.back().mapped, data, bytes);
        return vplkit::BufferView{buffers_.back().buffer, 0, bytes, name};
    };
    auto upload = [&](const auto& v, const char* name) { return buffer(v.size() * sizeof(v[0]), name, v.data()); };
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
    sources_ = sources.views(buffer(sources.bytes(), "vpl sources"));
    sources.write(buffers_.back().mapped);
    const vplkit::Bvh bvh = vplkit::build_bvh(triangles);
    const vplkit::BufferView nodes = upload(bvh.nodes, "bvh nodes"),
                             triangle_records = upload(bvh.triangles, "bvh triangles");
    const vplkit::BufferView alpha = upload(std::vector<uint32_t>{0}, "bvh alpha");  // opaque: no alpha records
    bvh_ = {nodes, triangle_records, uint32_t(bvh.nodes.size()), uint32_t(bvh.triangles.size()), bvh.scene_scale, alpha,
            false};

    // The chain: hybrid + SVGF at the renderer's size, reading its octahedral normals; every
    // buffer and image it lists comes from the renderer's own allocator.
    vs::GiChainOptions options;
    options.width = targets.colour.width;
    options.height = targets.colour.height;
    options.hybrid.samples_per_pixel = 16;
    options.adapter.normal_encoding = vs::GbufferNormalEncoding::octahedral;
    options.adapter.roughness = -1.0f;  // the renderer's surfaces are Lambertian
    chain_ = std::make_unique<vs::GiChain>(
        *kit_, options, [&](const vs::BufferRequirement& r) { return buffer(r.bytes, r.name, nullptr, r.usage); },
        [&](const vs::ImageRequirement& r) {
            images_.push_back(GpuImage::create(gpu, r.width, r.height, r.format, r.usage));
            gpu.submit([&](VkCommandBuffer cmd) {
                transition(cmd, images_.back(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
            });
            return view(images_.back(), r.name);
        });
}

void IndirectLight::record_gi(VkCommandBuffer cmd, const Camera& camera, uint32_t frame) {
    vplkit::StepList steps;
    const Rasterizer& r = *targets_;  // its depth, octahedral world normal and albedo: the chain's G-buffer
    const vs::GbufferAdapterInputs gbuffer{view(r.depth, "depth"), view(r.normal, "normal"), view(r.albedo, "albedo")};
    chain_->add_gi_passes(steps, {bvh_, sources_, gbuffer}, {frame, camera.eye, camera.view_projection});
    record(cmd, steps);
}

void IndirectLight::record_denoise_and_compose(VkCommandBuffer cmd, const Camera& camera, uint32_t frame) {
    vplkit::StepList steps;
    chain_->add_denoise_passes(steps, {frame, camera.eye, camera.view_projection});
    vs::add_compose_pass(*kit_, steps, view(targets_->colour, "colour"), chain_->indirect(),
                         view(targets_->output, "output"));
    record(cmd, steps);
}

void IndirectLight::record(VkCommandBuffer cmd, const vplkit::StepList& steps) const {
    barriers(cmd, steps.entry(), /*before_kit=*/true);  // the renderer's writes before the kit's steps...
    steps.record(cmd);                                  // (barriers between the kit's own steps are the kit's)
    barriers(cmd, steps.exit(), /*before_kit=*/false);  // ...and the kit's before the renderer's next commands
}

const GpuImage& IndirectLight::indirect() const {
    const VkImage image = chain_->indirect().image;
    return *std::find_if(images_.begin(), images_.end(), [&](const GpuImage& i) { return i.image == image; });
}

std::vector<vplkit::shaders::Vpl> IndirectLight::traced_vpls() const {
    const uint32_t count = std::min(*static_cast<const uint32_t*>(mapped(buffers_, chain_->vpls().count)),
                                    chain_->requirements().vpl_capacity);  // the tracer counts attempts past it
    const auto* first = static_cast<const vplkit::shaders::Vpl*>(mapped(buffers_, chain_->vpls().vpls));
    return {first, first + count};
}

void IndirectLight::destroy() {
    for (HostBuffer& b : buffers_) b.destroy(*gpu_);
    for (GpuImage& i : images_) i.destroy(*gpu_);
    kit_->destroy_pipelines();
}

}  // namespace dropin
