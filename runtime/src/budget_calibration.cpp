// The budget's calibration frames (budget_calibration.hpp). Per method, resolution and block
// size: two frames at spp0 with other random numbers and two at a second spp1 (the noise and how
// it falls with spp, and four cost samples); per method, runs of 3 svgf frames at both spp (svgf's
// floor and kept noise on this scene). Once: four frames at 64 spp, a pair with the settings' VPL
// budget and a pair with the space's smallest (the smaller budget's error), and frames at half the
// size, with and without svgf (the cost per pixel). An untimed frame first compiles the shaders
// and fixes the exposure.

#include "vplkit/budget_calibration.hpp"

#include "budget_cache.hpp"
#include "vplkit/budget_error.hpp"
#include "vplkit/budget_noise.hpp"
#include "vplkit/cache_key.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace vplkit {
namespace {

// svgf runs as the bench runs it: 3 frames, the last compared.
constexpr uint32_t kSvgfFrames = 3;
// The spp of the VPL budget's frames: the most the space allows.
constexpr uint32_t kReferenceSpp = 64;

// One frame to render: a configuration, its size, seed and frame counter.
struct CalibrationFrame {
    BudgetConfig config;
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t seed = 0;
    uint32_t frame = 0;
};

// The settings every calibration frame shares: nothing reused, a fixed exposure, no
// anti-aliasing (it would average frames), nothing read back but the image.
RenderSettings calibration_base(RenderSettings base) {
    base.reuse_static_work = false;
    base.antialias = false;
    base.vpls_only = false;
    base.read_back_aovs = false;
    base.force_all_stages = false;
    base.progress = nullptr;
    base.smc_warmup_progress = nullptr;
    return base;
}

RenderSettings frame_settings(const RenderSettings& base, const CalibrationFrame& f, VplSource source) {
    RenderSettings s = apply_budget_config(base, f.config, source);
    s.width = f.width;
    s.height = f.height;
    s.seed = f.seed;
    s.frame = f.frame;
    return s;
}

// Two frames run the same shaders at the same size (so the second compiles nothing and
// allocates nothing anew).
bool same_pipelines(const CalibrationFrame& a, const CalibrationFrame& b) {
    return a.config.method == b.config.method && a.config.half_resolution == b.config.half_resolution &&
           a.config.denoise == b.config.denoise && a.config.block_size == b.config.block_size && a.width == b.width &&
           a.height == b.height;
}

std::vector<uint32_t> blocks_of(GiMethod method, const BudgetSpace& space) {
    // A method without blocks (sst) builds no cuts: one block size stands for all.
    if (!gi_method(method).blocks) return {space.block_sizes.front()};
    return space.block_sizes;
}

// The entries of `list` without repeats, in the order given (so the first is the space's first).
template <typename T>
std::vector<T> unique_in_order(const std::vector<T>& list) {
    std::vector<T> out;
    for (const T& v : list) {
        if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
    }
    return out;
}

// The tonemapped frame on the bench's scale (sRGB / 255), 3 values a pixel.
std::vector<float> unit_rgb(const RenderedImage& image) {
    std::vector<float> rgb(image.rgba8.size() / 4 * 3);
    for (size_t p = 0; p < rgb.size() / 3; ++p) {
        for (size_t c = 0; c < 3; ++c) rgb[p * 3 + c] = float(image.rgba8[p * 4 + c]) / 255.0f;
    }
    return rgb;
}

}  // namespace

BudgetSpace default_budget_space(const RenderSettings& base, VplSource source) {
    BudgetSpace space;
    const uint32_t v = vpl_count_knob(base, source);
    space.vpls = v >= 4 ? std::vector<uint32_t>{v / 4, v} : std::vector<uint32_t>{v};
    space.block_sizes = {base.block_size};
    return space;
}

void validate_budget_space(const BudgetSpace& space) {
    if (space.methods.empty() || space.spp.empty() || space.half_resolution.empty() || space.denoise.empty() ||
        space.vpls.empty() || space.block_sizes.empty()) {
        throw Error(
            "budget: every list of the space (methods, spp, resolutions, denoisers, VPL budgets, "
            "block sizes) needs an entry");
    }
    for (GiMethod m : space.methods) {
        if (!gi_method(m).budget) {
            throw Error(std::string("budget: `method` ") + gi_method_name(m) +
                        " cannot be chosen by the budget (only " + gi_method_names(&GiMethodInfo::budget) +
                        ": the methods that trade samples for time with a noise the frame shows)");
        }
    }
    for (uint32_t n : space.spp) {
        if (n < 1 || n > 64) throw Error("budget: `samples_per_pixel` " + std::to_string(n) + " is not in 1..64");
    }
    for (uint32_t b : space.block_sizes) {
        if (b < 1 || b > 32) throw Error("budget: `block_size` " + std::to_string(b) + " is not in 1..32");
    }
    for (uint32_t v : space.vpls) {
        if (v == 0) throw Error("budget: a VPL budget of 0");
    }
    for (DenoiseMode d : space.denoise) {
        if (d == DenoiseMode::temporal) {
            throw Error(
                "budget: `denoise` temporal is not modelled (its effect depends on how long the camera "
                "stays still); off and svgf are");
        }
    }
}

BudgetCalibration calibrate_budget(Renderer& renderer, const DeviceInfo& device, const scene::Scene& scene,
                                   const scene::Camera& camera, const RenderSettings& base_settings,
                                   const BudgetSpace& space, const BudgetCalibrationOptions& options) {
    validate_budget_space(space);
    for (uint32_t n : {options.calibration_spp, options.second_spp}) {
        if (n < 1 || n > 64) throw Error("budget: a calibration spp of " + std::to_string(n) + " is not in 1..64");
    }
    const auto start = std::chrono::steady_clock::now();
    RenderSettings base = calibration_base(base_settings);
    const VplSource source = plan_frame(scene, base, "budget").vpl_source;
    const uint32_t w = base.width, h = base.height;
    const uint32_t spp0 = options.calibration_spp, spp1 = options.second_spp;
    const uint32_t v0 = vpl_count_knob(base, source);
    const uint32_t v_small = *std::min_element(space.vpls.begin(), space.vpls.end());
    const GiMethod m0 = space.methods.front();
    // The VPL budget's frames by an unbiased method (bias floor 0 in the method table: rtslc)
    // where the space has one: sst's substitutes smooth over the VPL set's blotches that the exact
    // frame shows.
    const auto unbiased = std::find_if(space.methods.begin(), space.methods.end(),
                                       [](GiMethod m) { return gi_method(m).bias_floor == 0.0; });
    const GiMethod m_vpl = unbiased != space.methods.end() ? *unbiased : m0;
    const bool half0 = space.half_resolution.front();
    const uint32_t b0 = space.block_sizes.front();
    auto config = [&](GiMethod m, uint32_t spp, bool half, DenoiseMode d, uint32_t vpls, uint32_t block) {
        return BudgetConfig{m, spp, half, d, vpls, block};
    };

    // The frames, and which pairs of them measure noise.
    std::vector<CalibrationFrame> frames;
    std::vector<std::pair<size_t, size_t>> noise_pairs;  // the first is (m0, half0, b0)'s
    for (GiMethod m : unique_in_order(space.methods)) {
        for (bool half : unique_in_order(space.half_resolution)) {
            for (uint32_t b : blocks_of(m, space)) {
                noise_pairs.emplace_back(frames.size(), frames.size() + 1);
                frames.push_back({config(m, spp0, half, DenoiseMode::off, v0, b), w, h, base.seed, 1});
                frames.push_back({config(m, spp0, half, DenoiseMode::off, v0, b), w, h, base.seed, 2});
                frames.push_back({config(m, spp1, half, DenoiseMode::off, v0, b), w, h, base.seed, 3});
                frames.push_back({config(m, spp1, half, DenoiseMode::off, v0, b), w, h, base.seed, 5});
            }
        }
    }
    // The VPL budget's error: two frames at kReferenceSpp (rtslc's where the space has it) with the
    // settings' VPL budget and two with the space's smallest: the error a smaller budget adds
    // against the frame over the settings' VPLs (vpl_set_variance: at this spp, low-passed, the
    // sampling noise beside it is small).
    const size_t reference_first = frames.size();
    if (v_small != v0) {
        frames.push_back({config(m_vpl, kReferenceSpp, half0, DenoiseMode::off, v0, b0), w, h, base.seed, 6});
        frames.push_back({config(m_vpl, kReferenceSpp, half0, DenoiseMode::off, v0, b0), w, h, base.seed, 7});
        frames.push_back({config(m_vpl, kReferenceSpp, half0, DenoiseMode::off, v_small, b0), w, h, base.seed, 8});
        frames.push_back({config(m_vpl, kReferenceSpp, half0, DenoiseMode::off, v_small, b0), w, h, base.seed, 9});
    }
    const uint32_t w2 = std::max(w / 2, 1u), h2 = std::max(h / 2, 1u);
    frames.push_back({config(m0, spp0, half0, DenoiseMode::off, v0, b0), w2, h2, base.seed, 1});
    // svgf's effect on this scene, per method: a run of 3 filtered frames (frame 0 starts the
    // history; the last is what the bench compares) at spp0 and one at spp1, each set against the
    // method's raw pair at spp1 (its noise, its correlation over a cut's block, are the method's).
    const bool svgf = std::find(space.denoise.begin(), space.denoise.end(), DenoiseMode::svgf) != space.denoise.end();
    std::vector<std::pair<size_t, size_t>> svgf_runs;  // (noise pair, first filtered frame)
    if (svgf) {
        for (size_t pair = 0; pair < noise_pairs.size(); ++pair) {
            const BudgetConfig raw = frames[noise_pairs[pair].first].config;  // a copy: frames grows below
            const bool first_of_method = std::none_of(svgf_runs.begin(), svgf_runs.end(), [&](const auto& run) {
                return frames[noise_pairs[run.first].first].config.method == raw.method;
            });
            if (raw.half_resolution != half0 || !first_of_method) continue;
            svgf_runs.emplace_back(pair, frames.size());
            for (uint32_t spp : {spp0, spp1}) {
                for (uint32_t f = 0; f < kSvgfFrames; ++f) {
                    frames.push_back(
                        {config(raw.method, spp, half0, DenoiseMode::svgf, v0, raw.block_size), w, h, base.seed, f});
                }
            }
        }
        frames.push_back({config(m0, spp0, half0, DenoiseMode::svgf, v0, b0), w2, h2, base.seed, 0});
    }

    // The key: what the measurements depend on, the plans of every frame among them.
    std::string plans;
    for (const CalibrationFrame& f : frames) {
        const RenderSettings s = frame_settings(base, f, source);
        plans += describe_budget_config(f.config) + " " + std::to_string(f.width) + "x" + std::to_string(f.height) +
                 ": " + plan_frame(scene, s, "budget").summary() + "\n";
    }
    plans += "direct " + std::to_string(base.direct_samples) + " " + direct_sampler_name(base.direct_sampler) +
             " bounces " + std::to_string(base.vpl_bounces) + " rsm " + std::to_string(base.rsm_resolution) +
             " interleave " + std::to_string(base.interleave) + " seed " + std::to_string(base.seed) + " exposure " +
             (base.auto_exposure ? std::string("auto") : std::to_string(base.exposure)) + " spp " +
             std::to_string(spp0) + " " + std::to_string(spp1);
    // The view: what the camera sees decides the noise, and BRSM places its VPLs for it.
    char view[256];
    std::snprintf(view, sizeof(view), " camera %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g", camera.position.x,
                  camera.position.y, camera.position.z, camera.forward.x, camera.forward.y, camera.forward.z,
                  camera.up.x, camera.up.y, camera.up.z, camera.yfov);
    plans += view;
    std::string scene_id = options.scene_id;
    std::replace(scene_id.begin(), scene_id.end(), '\n', ' ');
    BudgetCalibration result;
    result.key = "device " + device.name + "; driver " + device.driver_name + " " + device.driver_info + "; scene " +
                 scene_id + "; size " + std::to_string(w) + "x" + std::to_string(h) + "; plans " + fnv1a_hex(plans);
    if (!options.cache_dir.empty()) {
        result.cache_file = detail::budget_cache_file(options.cache_dir, result.key);
        if (auto cached = detail::read_budget_cache(result.cache_file, result.key)) {
            result.model = std::move(*cached);
            result.from_cache = true;
            return result;
        }
    }

    // Untimed frames: the first fixes the exposure every timed frame then keeps (so the noise is
    // on the tonemap's scale the user sees, not a per-frame automatic one); one more before every
    // frame whose pipelines or size differ from the frame before it, since lavapipe compiles a
    // shader at its first dispatch and that time lands in the pass's GPU timestamps (a first
    // frame's G-buffer 16x, svgf's firefly spread 60x its later ones at 96x54), which would
    // otherwise be fitted as a fixed cost of every frame.
    std::vector<bool> warm_first(frames.size(), false);
    for (size_t i = 1; i < frames.size(); ++i) warm_first[i] = !same_pipelines(frames[i - 1], frames[i]);
    const uint32_t total =
        uint32_t(frames.size()) + 1 + uint32_t(std::count(warm_first.begin(), warm_first.end(), true));
    uint32_t done = 0;
    {
        const RenderedImage first = renderer.render(camera, frame_settings(base, frames.front(), source));
        base.exposure = first.exposure;
        base.auto_exposure = false;
    }
    if (options.progress) options.progress(++done, total);

    std::vector<RenderedImage> images(frames.size());
    for (size_t i = 0; i < frames.size(); ++i) {
        const RenderSettings s = frame_settings(base, frames[i], source);
        if (warm_first[i]) {
            renderer.render(camera, s);
            if (options.progress) options.progress(++done, total);
        }
        RenderedImage image = renderer.render(camera, s);
        const CostPoint point = cost_point(s, source);
        result.model.cost.add_frame(image.timings, point);
        // A stage that ran but recorded no timed pass took no GPU time.
        for (const PlannedStage& stage : image.plan.stages) {
            const uint32_t tag = stage_tag(stage.stage);
            const bool timed = std::any_of(image.timings.begin(), image.timings.end(),
                                           [&](const PassTiming& t) { return t.tag == tag; });
            if (stage.runs && !timed) result.model.cost.add_sample(tag, point, 0.0);
        }
        // Keep only what the noise needs (the images of the pairs and the VPL frame).
        image.timings.clear();
        images[i] = std::move(image);
        if (options.progress) options.progress(++done, total);
    }
    result.model.cost.fit();

    // Noise on the linear indirect light (the direct light's own sampling noise left out), put on
    // the tonemapped frame's scale by the ratio of the two frames' tonemapped to linear noise.
    auto tonemap_scale = [&](const RenderedImage& a, const RenderedImage& b) {
        const double linear = half_difference_variance(a.radiance, b.radiance);
        return linear > 0.0 ? half_difference_variance_rgba8(a.rgba8, b.rgba8) / linear : 0.0;
    };
    for (const auto& [first, second] : noise_pairs) {
        const RenderedImage& a = images[first];
        const RenderedImage& b = images[second];
        const RenderedImage& c = images[second + 1];
        const RenderedImage& d = images[second + 2];
        NoiseMeasurement m;
        m.method = frames[first].config.method;
        m.half_resolution = frames[first].config.half_resolution;
        m.block_size = frames[first].config.block_size;
        m.spp = spp0;
        m.variance = half_difference_variance(a.indirect, b.indirect) * tonemap_scale(a, b);
        const double at_spp1 = half_difference_variance(c.indirect, d.indirect) * tonemap_scale(c, d);
        m.exponent = spp_exponent(m.variance, spp0, at_spp1, spp1);
        result.model.error.sampling.push_back(m);
    }
    if (v_small != v0) {
        // The smaller budget's error, low-passed (vpl_set_variance), on the tonemapped frames (the
        // bench's scale, where a dark region's error weighs more than the linear light says): its
        // half-difference is half its mean squared error.
        const std::vector<float> r1 = unit_rgb(images[reference_first]);
        const std::vector<float> r2 = unit_rgb(images[reference_first + 1]);
        const std::vector<float> s1 = unit_rgb(images[reference_first + 2]);
        const std::vector<float> s2 = unit_rgb(images[reference_first + 3]);
        const uint32_t block = std::min({vpl_noise_block(w), w, h});
        result.model.error.vpl_measured = v0;
        result.model.error.vpl_small = v_small;
        result.model.error.vpl_small_mse = 2.0 * vpl_set_variance(r1, r2, s1, s2, w, h, block);
    }
    for (const auto& [pair, filtered_first] : svgf_runs) {
        // svgf's error at spp0 and spp1 on the tonemapped frames (its blur falls on edges and dark
        // corners, where the tone curve weighs an error otherwise than where the noise is), against
        // the 64 spp rtslc pair where there is one (unbiased over the same VPLs; at 16 spp the tone
        // curve's clipping of rare bright samples shifted the raw frames' mean in Breakfast), else
        // the method's raw pair at spp1: its half-differences from both less theirs from each
        // other, so no square of the pair's own noise is left in it; less the method's bias floor
        // (the model adds it beside) against rtslc; with the raw noise at spp0 and spp1, svgf_effect().
        const auto [first, second] = noise_pairs[pair];
        const bool rtslc_reference = v_small != v0 && gi_method(m_vpl).bias_floor == 0.0;
        const std::vector<float> c = unit_rgb(images[rtslc_reference ? reference_first : second + 1]);
        const std::vector<float> d = unit_rgb(images[rtslc_reference ? reference_first + 1 : second + 2]);
        const double reference_noise = half_difference_variance(c, d);
        const GiMethod method = frames[first].config.method;
        const double bias = rtslc_reference ? method_bias_floor(method) : 0.0;
        auto filtered_error = [&](size_t run) {
            const std::vector<float> filtered = unit_rgb(images[filtered_first + run * kSvgfFrames + kSvgfFrames - 1]);
            return half_difference_variance(filtered, c) + half_difference_variance(filtered, d) - reference_noise -
                   bias * bias;
        };
        const NoiseMeasurement& raw = result.model.error.sampling[pair];
        const double raw0 = raw.variance;
        const double raw1 = variance_at_samples(raw.variance, raw.spp, spp1, raw.exponent);
        const double e0 = filtered_error(0), e1 = filtered_error(1);
        if (auto effect = svgf_effect(raw0, e0, raw1, e1)) result.model.error.sampling[pair].svgf = *effect;
    }
    result.frames = total;
    result.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!result.cache_file.empty()) detail::write_budget_cache(result.cache_file, result.key, result.model);
    return result;
}

}  // namespace vplkit
