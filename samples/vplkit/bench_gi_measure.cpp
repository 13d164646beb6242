// One bench gi point rendered and measured (bench_gi_measure.hpp).

#include "bench_gi_measure.hpp"

#include "vplkit/error.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/image_metrics.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"

#include <algorithm>
#include <initializer_list>
#include <map>

namespace vplkit::cli {

namespace {

// Which group of the frame a pass belongs to, by the planner's stage of the pass.
bool owned_by(const PassTiming& pass, std::initializer_list<FrameStage> stages) {
    for (FrameStage stage : stages) {
        if (stage_owns_pass(stage, pass)) return true;
    }
    return false;
}

bool is_gi_pass(const PassTiming& pass) {
    return owned_by(pass, {FrameStage::gi_downsample, FrameStage::gi_exact, FrameStage::gi_sst, FrameStage::gi_rtslc,
                           FrameStage::gi_hybrid, FrameStage::gi_flc, FrameStage::gi_upsample});
}
bool is_tree_pass(const PassTiming& pass) {
    return owned_by(pass, {FrameStage::vpl_sort, FrameStage::light_tree, FrameStage::sst});
}
bool is_vpl_pass(const PassTiming& pass) {
    return owned_by(pass, {FrameStage::vpl_paths, FrameStage::brsm_vpls, FrameStage::flc_vpls});
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

bool measure_bench_point(Renderer& renderer, const scene::Camera& camera, RenderSettings s, uint32_t frames,
                         const std::vector<float>& truth_rgb, const std::vector<float>& truth_radiance,
                         const std::filesystem::path& out, BenchPoint& p, std::string& failure) {
    std::vector<double> frame_ms, gi_ms, trees_ms, vpls_ms;
    std::vector<std::string> stage_names;
    std::map<std::string, std::vector<double>> stage_ms;
    RenderedImage image;
    for (uint32_t f = 0; f < frames && failure.empty(); ++f) {
        try {
            if (p.denoised) s.frame = f;  // new samples each frame; frame 0 restarts the history
            image = renderer.render(camera, s);
        } catch (const Error& e) {
            // A point the device cannot run (e.g. a tree beyond its storage-buffer range) is
            // reported and skipped; the rest of the sweep goes on.
            failure = e.what();
            break;
        }
        if (f == 0 && frames > 1) continue;  // shader compiles at first dispatch
        double total = 0, gi = 0, trees = 0, vpls = 0;
        std::map<std::string, double> this_frame;
        for (const PassTiming& t : image.timings) {
            if (this_frame.count(t.name) == 0 && stage_ms.count(t.name) == 0) stage_names.push_back(t.name);
            this_frame[t.name] += t.gpu_ms;
            total += t.gpu_ms;
            if (is_gi_pass(t))
                gi += t.gpu_ms;
            else if (is_tree_pass(t))
                trees += t.gpu_ms;
            else if (is_vpl_pass(t))
                vpls += t.gpu_ms;
        }
        for (const auto& [name, ms] : this_frame) stage_ms[name].push_back(ms);
        frame_ms.push_back(total);
        gi_ms.push_back(gi);
        trees_ms.push_back(trees);
        vpls_ms.push_back(vpls);
    }
    if (!failure.empty()) {
        p.frames = 0;
        return false;
    }
    if (image.non_finite_pixels > 0) throw Error("bench: " + p.label() + " gave non-finite pixels");
    p.frames = uint32_t(frame_ms.size());
    p.frame_ms = median(frame_ms);
    p.frame_min_ms = *std::min_element(frame_ms.begin(), frame_ms.end());
    p.frame_max_ms = *std::max_element(frame_ms.begin(), frame_ms.end());
    p.gi_ms = median(gi_ms);
    p.trees_ms = median(trees_ms);
    p.vpls_ms = median(vpls_ms);
    for (const std::string& name : stage_names) {
        const std::vector<double>& v = stage_ms[name];
        p.stages.push_back(
            {name, median(v), *std::min_element(v.begin(), v.end()), *std::max_element(v.begin(), v.end())});
    }
    p.vpls = image.vpl_count;
    const std::vector<float> rgb = unit_rgb(image.rgba8);
    p.rmse = rmse(rgb, truth_rgb);
    p.ssim = ssim(rgb, truth_rgb, image.width, image.height);
    p.relmse = relative_mse(image.radiance, truth_radiance);
    p.levels_per_traversal = image.gi_counts.levels_per_traversal();
    p.mock_cut_pixels = image.gi_counts.mock_cut_pixels;
    p.dropped_samples = image.gi_counts.dropped_samples;
    std::string file = p.label();
    std::replace(file.begin(), file.end(), ' ', '_');
    p.image = "images/" + file + ".png";
    write_png(out / p.image, image.width, image.height, image.rgba8);
    return true;
}

}  // namespace vplkit::cli
