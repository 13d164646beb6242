#include "vplkit_gi.hpp"

#include "vplkit/stages/compose.hpp"

#include <algorithm>
#include <string>

namespace dropin {

namespace vs = vplkit::stages;

namespace {

vplkit::ImageView view(const GpuImage& i, const std::string& name) {
    return {i.image, i.view, i.format, i.width, i.height, name, i.aspect};  // no layout pointer
}

void* mapped(const std::vector<HostBuffer>& buffers, const vplkit::BufferView& v) {
    return std::find_if(buffers.begin(), buffers.end(), [&](const HostBuffer& h) { return h.buffer == v.buffer; })
        ->mapped;
}

}  // namespace

IndirectLight::IndirectLight(const Gpu& gpu, const Scene& scene, const Rasterizer& targets)
    : gpu_(&gpu), targets_(&targets), kit_(std::make_unique<vs::Device>(gpu.physical_device, gpu.device)) {
    auto buffer = [&](uint64_t bytes, const std::string& name, VkBufferUsageFlags usage) {
        buffers_.push_back(HostBuffer::create(gpu, bytes, usage));
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
    const vs::RendererSceneData data = vs::renderer_scene({&light, 1}, {}, {triangles, albedo});
    scene_ = data.views(buffer(data.bytes(), "scene", VK_BUFFER_USAGE_STORAGE_BUFFER_BIT));
    data.write(buffers_.back().mapped);

    // The chain: hybrid + SVGF at the renderer's size, reading its octahedral normals; every
    // buffer and image it lists comes from the renderer's own allocator.
    vs::GiChainOptions options;
    options.width = targets.colour.width;
    options.height = targets.colour.height;
    options.hybrid.samples_per_pixel = 16;
    options.adapter.normal_encoding = vs::GbufferNormalEncoding::octahedral;
    options.adapter.roughness = vs::kLambertianRoughness;  // the renderer's surfaces are all diffuse
    chain_ = std::make_unique<vs::GiChain>(
        *kit_, options, [&](const vs::BufferRequirement& r) { return buffer(r.bytes, r.name, r.usage); },
        [&](const vs::ImageRequirement& r) {
            images_.push_back(GpuImage::create(gpu, r.width, r.height, r.format, r.usage));
            return view(images_.back(), r.name);  // as created: the chain keeps its layout
        });
}

void IndirectLight::record_gi(VkCommandBuffer cmd, const Camera& camera, uint32_t frame) {
    vplkit::StepList steps;
    const Rasterizer& r = *targets_;  // its depth, octahedral world normal and albedo: the chain's G-buffer
    const vs::GbufferAdapterInputs gbuffer{view(r.depth, "depth"), view(r.normal, "normal"), view(r.albedo, "albedo")};
    chain_->add_gi_passes(steps, {scene_.bvh, scene_.sources, gbuffer},
                          vs::GiChainFrame::from_camera(frame, camera.view, camera.projection));
    steps.record_with_caller_barriers(cmd);  // after all the renderer's commands, before its next
}

void IndirectLight::record_denoise_and_compose(VkCommandBuffer cmd, const Camera& camera, uint32_t frame) {
    vplkit::StepList steps;
    chain_->add_denoise_passes(steps, vs::GiChainFrame::from_camera(frame, camera.view, camera.projection));
    vs::add_compose_pass(*kit_, steps, view(targets_->colour, "colour"), chain_->indirect(),
                         view(targets_->output, "output"));
    steps.record_with_caller_barriers(cmd);
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
