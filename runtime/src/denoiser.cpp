#include "vplkit/denoiser.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"

#include <array>

namespace vplkit {

namespace {

Image float4(Context& context, uint32_t w, uint32_t h, const char* name) {
    return Image::create(context, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, name);
}

}  // namespace

Denoiser Denoiser::create(Context& context, uint32_t w, uint32_t h) {
    Denoiser d;
    d.irradiance_ = float4(context, w, h, "denoise irradiance");
    d.clamped_ = float4(context, w, h, "denoise clamped");
    d.excess_ = float4(context, w, h, "denoise firefly excess");
    d.spread_ = float4(context, w, h, "denoise firefly spread");
    d.accumulated_ = float4(context, w, h, "denoise accumulated");
    d.estimated_ = float4(context, w, h, "denoise variance");
    d.ping_ = float4(context, w, h, "denoise a-trous ping");
    d.pong_ = float4(context, w, h, "denoise a-trous pong");
    for (History& s : d.history_) {
        s = {float4(context, w, h, "denoise history position"), float4(context, w, h, "denoise history normal"),
             float4(context, w, h, "denoise history color"), float4(context, w, h, "denoise history moments")};
    }
    return d;
}

void Denoiser::add_passes(Context& context, StepList& passes, DenoiseMode mode, const stages::GbufferViews& gbuffer,
                          Image& indirect, const stages::DenoiseOptions& options, bool demodulated) {
    if (mode == DenoiseMode::off) throw Error("denoiser: no filter asked for (`denoise` off)");
    if (gbuffer.width() != width() || gbuffer.height() != height()) {
        throw Error("denoiser: the G-buffer's size differs from the denoiser's");
    }
    History& previous = history_[1 - current_];
    History& next = history_[current_];
    ImageView input = indirect;
    if (!demodulated) {
        stages::add_demodulate_pass(context, passes, indirect, gbuffer.albedo, gbuffer.position, irradiance_, options);
        input = irradiance_;
    }
    // Temporal only: the accumulated colour is the history. SVGF: the first a-trous iteration is.
    const bool spatial = mode == DenoiseMode::svgf && options.atrous_iterations > 0;
    // SVGF's history is the filtered image, so each frame puts it through the a-trous step once
    // more: without a cap a static view would be blurred without end. The cap stays there; only
    // temporal accumulation (history = the running mean itself) drops it on a static view.
    stages::DenoiseOptions temporal_options = options;
    if (spatial) temporal_options.static_max_history = options.max_history;
    Image& accumulated = spatial ? accumulated_ : next.color;
    stages::add_temporal_accumulate_pass(context, passes, input, gbuffer.position, gbuffer.normal, previous.views(),
                                         next.views(), accumulated, next.moments, previous_view_projection_,
                                         has_history_, temporal_options, gbuffer.motion);
    ImageView result = accumulated;
    variance_from_ = spatial ? 2 : int(current_);
    // The firefly clamp acts on the accumulated image, not on the frame: the history keeps the
    // unclamped mean (unbiased, so a static view converges), and the clamp, which keeps the
    // light anyway, shapes only what is shown and filtered.
    clamped_this_frame_ = options.firefly_k_sigma > 0.0f;
    if (clamped_this_frame_) {
        stages::add_firefly_clamp_passes(context, passes, accumulated, next.moments, gbuffer.albedo, gbuffer.position,
                                         clamped_, excess_, spread_, options);
        result = spread_;
    }
    if (spatial) {
        stages::add_variance_estimate_pass(context, passes, result, next.moments, gbuffer.position, gbuffer.normal,
                                           estimated_, options);
        ImageView source = estimated_;
        // irradiance_ and accumulated_ are read by nothing after the variance estimate (the clamp's
        // images are: firefly_moved_fraction), so the a-trous iterations work in them.
        const stages::AtrousScratch scratch{irradiance_, accumulated_};
        for (uint32_t i = 0; i < options.atrous_iterations; ++i) {
            ImageView target = i == 0 ? ImageView(next.color) : (i % 2 == 1 ? ImageView(ping_) : ImageView(pong_));
            stages::add_atrous_passes(context, passes, source, gbuffer.position, gbuffer.normal, scratch, target,
                                      1 << i, options);
            source = target;
        }
        result = source;
    }
    stages::add_remodulate_pass(context, passes, result, gbuffer.albedo, indirect, options);
}

void Denoiser::end_frame(const glm::mat4& view_projection) {
    previous_view_projection_ = view_projection;
    has_history_ = true;
    current_ = 1 - current_;
}

double Denoiser::firefly_moved_fraction() {
    if (!clamped_this_frame_) return 0.0;
    // Irradiance luminance taken off (excess.a) over what the clamp was given (kept + taken off).
    double taken = 0.0, given = 0.0;
    for (const auto& t : excess_.download<std::array<float, 4>>()) taken += t[3];
    for (const auto& t : clamped_.download<std::array<float, 4>>())
        given += 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2];
    given += taken;
    return given > 0.0 ? taken / given : 0.0;
}

std::vector<float> Denoiser::variance() {
    std::vector<float> out;
    if (variance_from_ < 0) return out;
    Image& image = variance_from_ == 2 ? estimated_ : history_[variance_from_].color;
    for (const auto& t : image.download<std::array<float, 4>>()) out.push_back(t[3]);
    return out;
}

}  // namespace vplkit
