// --denoise on whole frames (the in-repo Cornell box, 64 x 64, BRSM VPLs, hybrid 8 spp):
// - temporal accumulation on a static camera, without the firefly clamp, is exactly the per-pixel
//   mean of the raw frames (demodulation and remodulation cancel; reprojection is the identity):
//   within 1e-4 relative (float sums of F values);
// - svgf over 4 frames is closer to exact than one raw frame (relative RMSE at most half; measured
//   0.145 against 0.503) and keeps the raw frame's light within 3% (measured 0.981: the a-trous
//   weights are normalized per pixel, not mass-preserving, and the frames differ in their samples).

#include "vplkit/context.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/sequence_metrics.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/trigonometric.hpp>

#include <cmath>
#include <vector>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace {

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";

vplkit::RenderSettings small_frame(vplkit::GiMethod method) {
    vplkit::RenderSettings s;
    s.width = 64;
    s.height = 64;
    s.method = method;
    s.vpl_source = vplkit::VplSource::brsm;
    s.brsm.vpl_count = 512;
    s.rsm_resolution = 128;
    s.samples_per_pixel = 8;
    return s;
}

double sum(const std::vector<float>& v) {
    double s = 0.0;
    for (float x : v) s += x;
    return s;
}

double relative_rmse(const std::vector<float>& image, const std::vector<float>& truth) {
    double e = 0.0, t = 0.0;
    for (size_t i = 0; i < image.size(); ++i) {
        e += (double(image[i]) - truth[i]) * (double(image[i]) - truth[i]);
        t += double(truth[i]) * truth[i];
    }
    return std::sqrt(e / t);
}

}  // namespace

TEST_CASE("denoise render: temporal accumulation on a static camera is the mean of the raw frames") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    constexpr uint32_t kFrames = 4;
    auto raw = small_frame(vplkit::GiMethod::hybrid);
    std::vector<double> mean;
    for (uint32_t f = 0; f < kFrames; ++f) {
        raw.frame = f;
        const auto image = renderer.render(scene.camera(), raw);
        if (mean.empty()) mean.assign(image.indirect.size(), 0.0);
        for (size_t i = 0; i < mean.size(); ++i) mean[i] += image.indirect[i] / kFrames;
    }
    auto temporal = raw;
    temporal.denoise = vplkit::DenoiseMode::temporal;
    temporal.denoise_options.firefly_k_sigma = 0.0f;
    vplkit::RenderedImage image;
    for (uint32_t f = 0; f < kFrames; ++f) {
        temporal.frame = f;
        image = renderer.render(scene.camera(), temporal);
    }
    double worst = 0.0, scale = 0.0;
    for (double m : mean) scale = std::max(scale, m);
    for (size_t i = 0; i < mean.size(); ++i) worst = std::max(worst, std::abs(image.indirect[i] - mean[i]));
    MESSAGE("largest difference from the raw frames' mean: " << worst << " (largest value " << scale << ")");
    CHECK(worst <= 1e-4 * scale);
}

TEST_CASE("denoise render: svgf over 4 frames halves the error of one raw frame and keeps its light") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    const auto truth = renderer.render(scene.camera(), small_frame(vplkit::GiMethod::exact)).indirect;
    auto settings = small_frame(vplkit::GiMethod::hybrid);
    const auto raw = renderer.render(scene.camera(), settings).indirect;
    settings.denoise = vplkit::DenoiseMode::svgf;
    std::vector<float> filtered;
    for (uint32_t f = 0; f < 4; ++f) {
        settings.frame = f;
        filtered = renderer.render(scene.camera(), settings).indirect;
    }
    const double raw_error = relative_rmse(raw, truth), filtered_error = relative_rmse(filtered, truth);
    MESSAGE("relative RMSE against exact: raw " << raw_error << ", svgf over 4 frames " << filtered_error
                                                << "; mean over raw's " << sum(filtered) / sum(raw));
    CHECK(filtered_error < 0.5 * raw_error);
    CHECK(sum(filtered) / sum(raw) == doctest::Approx(1.0).epsilon(0.03));
}

TEST_CASE("denoise render: along an orbit svgf lowers |E'| and does not raise |E|") {
    // Seed 001's metrics (runtime/sequence_metrics) over 6 frames of a 6-degree orbit in the
    // in-repo Cornell box, 48 x 48, hybrid 8 spp over one set of IR VPLs (512 paths), against the
    // exact gather over 2048 IR paths. Measured: |E'| 0.092 -> 0.0090 with svgf, |E| 0.071 -> 0.025; the
    // checks ask for 2x and "not higher".
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    const vplkit::scene::Camera file_camera = scene.camera();
    auto settings = small_frame(vplkit::GiMethod::hybrid);
    settings.width = settings.height = 48;
    settings.vpl_source = vplkit::VplSource::ir;
    settings.vpl_paths = 512;
    auto reference = settings;
    reference.method = vplkit::GiMethod::exact;
    reference.vpl_paths = 2048;
    reference.seed = 1000003;
    vplkit::Renderer renderer(ctx, scene), reference_renderer(ctx, scene);
    vplkit::TemporalErrorMeter off, svgf;
    for (uint32_t f = 0; f < 6; ++f) {
        const float a = glm::radians(6.0f * float(f) / 5.0f);
        vplkit::scene::Camera camera =
            vplkit::scene::look_at(glm::vec3(3.4f * std::sin(a), 1.0f, 3.4f * std::cos(a)), glm::vec3(0, 1, 0),
                                   glm::vec3(0, 1, 0), glm::radians(45.0f));
        camera.znear = file_camera.znear > 0.0f ? file_camera.znear : 0.01f;
        camera.zfar = file_camera.zfar;
        const auto truth = vplkit::reinhard_luminance(reference_renderer.render(camera, reference).indirect);
        settings.frame = f;
        settings.denoise = vplkit::DenoiseMode::off;
        off.add_frame(vplkit::reinhard_luminance(renderer.render(camera, settings).indirect), truth);
        settings.denoise = vplkit::DenoiseMode::svgf;
        svgf.add_frame(vplkit::reinhard_luminance(renderer.render(camera, settings).indirect), truth);
    }
    const auto& o = off.result();
    const auto& s = svgf.result();
    MESSAGE("|E| " << o.average_error() << " -> " << s.average_error() << ", |E'| " << o.average_error_change()
                   << " -> " << s.average_error_change());
    CHECK(s.average_error_change() < 0.5 * o.average_error_change());
    CHECK(s.average_error() <= o.average_error());
}
