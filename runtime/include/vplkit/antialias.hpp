#pragma once
// Anti-aliasing by accumulation on a static camera (RenderSettings::antialias): each frame's
// G-buffer is rastered with a sub-pixel offset of the projection, so an edge covers a pixel in
// some frames and not in others, and the output is the mean of the frames: the pixel's coverage.
// Only the raster pass sees the offset; every other stage (the denoiser's reprojection with the
// previous camera, BRSM's view, the splats) gets the camera's un-jittered matrices, so the
// jitter never counts as motion.

#include "vplkit/stages/gbuffer.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace vplkit {

// The offset of frame `frame`, in pixels, in [-0.5, 0.5)^2: 0 for frame 0 (the pixel centres, as
// without anti-aliasing, so one frame is unchanged), then the Halton(2,3) points 1, 2, ...
// less 0.5 (well spread for any number of frames; the sequence repeats after 1024 frames).
glm::vec2 subpixel_jitter(uint32_t frame);

// `view` with its clip space shifted by `offset` pixels of a width x height image (x right, y down).
stages::CameraView jittered_view(const stages::CameraView& view, glm::vec2 offset, uint32_t width, uint32_t height);

// The running mean of the frames' direct and indirect light (3 floats per pixel).
class FrameAccumulator {
public:
    // Adds a frame and replaces `direct` (and `indirect` when `average_indirect`; a denoiser
    // already accumulates it) by the mean since the accumulation began, and `radiance` by their
    // sum. Starts afresh at frame 0 and when the size or the un-jittered `view_projection`
    // differs from the previous frame's. Returns `radiance` as RGBA (alpha 1), for the GPU image.
    std::vector<float> add(uint32_t frame, const glm::mat4& view_projection, bool average_indirect,
                           std::vector<float>& direct, std::vector<float>& indirect, std::vector<float>& radiance);

    uint32_t frames() const { return count_; }  // in the current mean

private:
    std::vector<float> direct_, indirect_;
    uint32_t count_ = 0;
    glm::mat4 view_projection_{1.0f};
};

}  // namespace vplkit
