#pragma once
// The runtime's denoiser: the history images of stages/denoise.hpp kept from frame to frame (two
// sets, swapped each frame), and one frame's passes in SVGF's order, except that the firefly
// clamp runs on the accumulated image (the history keeps the unclamped mean). The Renderer owns one.
//
//   Denoiser d = Denoiser::create(ctx, w, h);
//   d.add_passes(ctx, passes, mode, gbuffer, indirect, view_projection, options, demodulated);
//   passes.run(ctx);
//   d.end_frame(view_projection);   // what the next frame reprojects with

#include "vplkit/image.hpp"
#include "vplkit/render_settings.hpp"
#include "vplkit/stages/denoise.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/steps.hpp"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <vector>

namespace vplkit {

class Context;

class Denoiser {
public:
    static Denoiser create(Context& context, uint32_t width, uint32_t height);

    uint32_t width() const { return irradiance_.width(); }
    uint32_t height() const { return irradiance_.height(); }
    // A previous frame to reproject (false after create() and reset()).
    bool has_history() const { return has_history_; }
    void reset() { has_history_ = false; }

    // Filters `indirect` in place: radiance in, radiance out (mode temporal or svgf). `demodulated`:
    // `indirect` already holds irradiance (the half-resolution path demodulates before upsampling),
    // so only remodulation runs. `gbuffer` is this frame's, at this denoiser's size.
    void add_passes(Context& context, StepList& passes, DenoiseMode mode, const stages::GbufferViews& gbuffer,
                    Image& indirect, const stages::DenoiseOptions& options, bool demodulated);
    // After the passes ran: this frame becomes the history; `view_projection` is its camera's.
    void end_frame(const glm::mat4& view_projection);

    // The firefly clamp's last frame: the share of the accumulated irradiance's luminance it took
    // off outliers and spread over their neighbours (none of it is lost: the spread keeps the
    // remodulated sum, tests/denoise). Downloads two images; 0 when the clamp is off.
    double firefly_moved_fraction();
    // The last frame's luminance variance of the demodulated indirect light, a float per pixel,
    // rows top to bottom: what the a-trous filter weighs by (svgf), or the running variance of
    // the accumulation (temporal). Downloads one image; empty before the first frame.
    std::vector<float> variance();

private:
    struct History {
        Image position, normal, color, moments;
        stages::DenoiseHistory views() { return {position, normal, color, moments}; }
    };
    Image irradiance_, clamped_, excess_, spread_, accumulated_, estimated_, ping_, pong_;
    History history_[2];
    uint32_t current_ = 0;  // the history set this frame writes
    bool has_history_ = false;
    bool clamped_this_frame_ = false;
    // Whose alpha holds the last frame's variance: history_[i].color (0, 1), estimated_ (2), none (-1).
    int variance_from_ = -1;
    glm::mat4 previous_view_projection_{1.0f};
};

}  // namespace vplkit
