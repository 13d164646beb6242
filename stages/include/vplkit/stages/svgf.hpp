#pragma once
// SVGF in one call: the denoise passes of denoise.hpp chained as the runtime's Denoiser chains
// them (vplkit/denoiser.hpp), for a renderer that takes the kit's GI stages one by one:
//
//   demodulate -> temporal accumulation (reprojected history) -> firefly clamp (unless
//   firefly_k_sigma is 0) -> variance -> a-trous x atrous_iterations (the first iteration's
//   output is the next frame's history) -> remodulate, in place
//
// With atrous_iterations = 0 it is temporal accumulation alone (the history is the running mean).
//
//   std::vector<vplkit::ImageView> svgf_images(kSvgfImageCount);   // RGBA32F, the frame's size
//   vplkit::stages::add_svgf_passes(device, steps, gbuffer, indirect, svgf_images,
//                                   {frame, view_projection, previous_view_projection}, options);

#include "vplkit/stages/denoise.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <span>

namespace vplkit::stages {

// The images the chain works in: RGBA32F, the frame's size, storage usage, GENERAL layout,
// passed in one span, the same ones in the same order every frame (two frames' history lives in
// them; what each holds is the chain's business).
inline constexpr uint32_t kSvgfImageCount = 16;

struct SvgfFrame {
    // Frames since the history started: 0 starts it over (the first frame, a cut, a resize).
    // Its parity picks which half of the history images this frame writes.
    uint32_t index = 0;
    glm::mat4 view_projection{1.0f};           // this frame's world -> Vulkan clip
    glm::mat4 previous_view_projection{1.0f};  // the previous frame's (unused when index is 0)
};

// Adds the chain. Reads the G-buffer's position, normal and albedo; reads `radiance` (RGBA32F,
// the GI stage's output) and writes the denoised radiance back to it. Throws vplkit::Error for a
// span that is not kSvgfImageCount images, bad options (validate(DenoiseOptions)), or what the
// passes throw (formats, sizes).
void add_svgf_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const ImageView& radiance,
                     std::span<const ImageView> images, const SvgfFrame& frame, const DenoiseOptions& options);

}  // namespace vplkit::stages
