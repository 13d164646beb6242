#pragma once
// Everything that stands between the sample's renderer (renderer.hpp) and vplkit: one-bounce
// indirect light recorded into the renderer's command buffer each frame, with nothing read back.
// The kit's GI chain (vplkit/stages/gi_chain.hpp) does the stages:
//
//   VPLs traced from the renderer's light and triangles (count kept on the GPU) -> Morton keys
//   -> radix sort -> leaves -> SST -> G-buffer from the renderer's depth, normal and albedo
//   -> hybrid GI -> SVGF; then compose colour + indirect into the renderer's RGBA16F output.
//
// What is left here: the scene in the kit's terms and memory for what the chain lists (the
// barriers between the renderer's commands and the kit's steps are the StepList's).

#include "plain_vulkan.hpp"
#include "renderer.hpp"

#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/gi_chain.hpp"
#include "vplkit/stages/renderer_scene.hpp"

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
    const GpuImage& indirect() const;
    float scene_scale() const { return scene_.bvh.scene_scale; }

private:
    const Gpu* gpu_;
    const Rasterizer* targets_;
    std::unique_ptr<vplkit::stages::Device> kit_;
    std::vector<HostBuffer> buffers_;
    std::vector<GpuImage> images_;
    vplkit::stages::RendererSceneBuffers scene_;
    std::unique_ptr<vplkit::stages::GiChain> chain_;
};

}  // namespace dropin
