#pragma once
// Everything that stands between the sample's renderer (renderer.hpp) and vplkit: one-bounce
// indirect light recorded into the renderer's command buffer each frame, with nothing read back:
//
//   VPLs traced from the renderer's light and triangles (count kept on the GPU) -> Morton keys
//   -> radix sort -> leaves -> SST -> G-buffer from the renderer's depth, normal and albedo
//   -> hybrid GI -> SVGF -> compose colour + indirect into the renderer's RGBA16F output

#include "plain_vulkan.hpp"
#include "renderer.hpp"

#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/stages/hybrid_gi.hpp"
#include "vplkit/stages/radix_sort.hpp"
#include "vplkit/stages/sst.hpp"
#include "vplkit/stages/svgf.hpp"
#include "vplkit/stages/vpl_keys.hpp"
#include "vplkit/stages/vpl_tracing.hpp"

#include <glm/mat4x4.hpp>

#include <memory>
#include <vector>

namespace dropin {

class IndirectLight {
public:
    IndirectLight(const Gpu& gpu, const Scene& scene, const Rasterizer& targets);
    // After the raster pass: this frame's VPLs (seed `frame`) and their light into indirect().
    void record_gi(VkCommandBuffer cmd, const Camera& camera, uint32_t frame);
    // Then SVGF on indirect() and colour + indirect into the renderer's output.
    void record_denoise_and_compose(VkCommandBuffer cmd, const Camera& camera, uint32_t frame);
    void destroy();

    // For the sample's check: the VPLs the last frame traced (after its submission), the GI
    // before the denoiser (RGBA32F, GENERAL) and the scene scale the kit's lengths are shares of.
    std::vector<vplkit::shaders::Vpl> traced_vpls() const;
    const GpuImage& indirect() const { return images_[indirect_image_]; }
    float scene_scale() const { return bvh_.scene_scale; }

private:
    void record(VkCommandBuffer cmd, const vplkit::StepList& steps);

    const Gpu* gpu_;
    const Rasterizer* targets_;
    std::unique_ptr<vplkit::stages::Device> kit_;
    std::vector<HostBuffer> buffers_;
    std::vector<GpuImage> images_;
    size_t indirect_image_ = 0;
    std::unique_ptr<vplkit::stages::RadixSorter> sorter_;
    vplkit::stages::VplSourceBuffers sources_;
    vplkit::stages::BvhBuffers bvh_;
    vplkit::stages::VplTracingBuffers tracing_;
    vplkit::stages::VplKeyBuffers keys_;
    vplkit::stages::VplTreeBuffers trees_;
    vplkit::BufferView sst_counters_, gi_counters_;
    vplkit::stages::HybridCutBuffers cuts_;
    vplkit::stages::GbufferViews gbuffer_;
    vplkit::ImageView indirect_;
    std::vector<vplkit::ImageView> svgf_{vplkit::stages::kSvgfImageCount};
    glm::mat4 previous_{1.0f};
    vplkit::stages::SstOptions sst_;
    vplkit::stages::HybridOptions hybrid_;
    vplkit::stages::DenoiseOptions denoise_;  // the defaults, lengths as shares of the scene scale
};

}  // namespace dropin
