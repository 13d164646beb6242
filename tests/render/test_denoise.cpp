// --denoise on whole frames (the in-repo Cornell box, 64 x 64, BRSM VPLs, hybrid 8 spp):
// - temporal accumulation on a static camera, without the firefly clamp, is exactly the per-pixel
//   mean of the raw frames (demodulation and remodulation cancel; reprojection is the identity):
//   within 1e-4 relative (float sums of F values);
// - svgf over 4 frames is closer to exact than one raw frame (relative RMSE at most half; measured
//   0.145 against 0.503) and keeps the raw frame's light within 3% (measured 1.006: the a-trous
//   weights preserve the image's light; the frames differ in their samples);
// - temporal accumulation with the firefly clamp on converges to exact (rtslc, 256 frames,
//   32 x 32): the clamp keeps the light and a static camera's history has no cap.

#include "vplkit/context.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/sequence_metrics.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/trigonometric.hpp>

#include <algorithm>
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

// Means over K x K blocks of pixels, per channel (full blocks only).
std::vector<double> block_means(const std::vector<float>& image, uint32_t width, uint32_t height, uint32_t k) {
    std::vector<double> out;
    for (uint32_t by = 0; by + k <= height; by += k)
        for (uint32_t bx = 0; bx + k <= width; bx += k)
            for (int c = 0; c < 3; ++c) {
                double s = 0.0;
                for (uint32_t y = by; y < by + k; ++y)
                    for (uint32_t x = bx; x < bx + k; ++x) s += image[(std::size_t(y) * width + x) * 3 + c];
                out.push_back(s / (k * k));
            }
    return out;
}

// sqrt(mean((a - b)^2)) / mean(b).
double relative_rmse(const std::vector<double>& image, const std::vector<double>& truth) {
    double e = 0.0, t = 0.0;
    for (size_t i = 0; i < image.size(); ++i) e += (image[i] - truth[i]) * (image[i] - truth[i]), t += truth[i];
    return std::sqrt(e / image.size()) / (t / image.size());
}

double brightest(const std::vector<float>& image) {
    double m = 0.0;
    for (size_t i = 0; i < image.size(); i += 3)
        m = std::max(m, 0.2126 * image[i] + 0.7152 * image[i + 1] + 0.0722 * image[i + 2]);
    return m;
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
    // The SMC paper's metrics (runtime/sequence_metrics) over 6 frames of a 6-degree orbit in the
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

TEST_CASE("denoise render: accumulation with the firefly clamp converges to exact (rtslc, static camera)") {
    // The in-repo Cornell box, 32 x 32, rtslc 8 spp over 512 BRSM VPLs, `--denoise temporal` with
    // the default clamp (4 sigma), 256 frames, against exact over the same VPLs. Unbiased frames
    // averaged with 1 / n weights have a 4 x 4-block error whose square is the one-frame block
    // error's square over F (plus a bias's square, if any); the one-frame value is measured here
    // over 8 raw frames (rms). Bounds, each a property a biased or capped accumulation breaks:
    // - mean within 1% of exact's (the old clamp dropped its excess: a dark bias; at 256 frames
    //   the mean's own noise is ~0.1%);
    // - block error at most 1.5x the one-frame value / sqrt(256) (the estimates' own spread, 64
    //   blocks x 3 channels, is ~15%; a history capped at 32 frames settles at sqrt(1/63) of the
    //   one-frame value, 2x the target);
    // - the brightest pixel within 25% of exact's (one frame's brightest pixel is several times
    //   exact's; after 256 frames a pixel's noise is 1/16 of one frame's).
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    constexpr uint32_t kSize = 32, kBlock = 4, kFrames = 256, kRawFrames = 8;
    auto settings = small_frame(vplkit::GiMethod::rtslc);
    settings.width = settings.height = kSize;
    auto exact_settings = settings;
    exact_settings.method = vplkit::GiMethod::exact;
    const auto truth = renderer.render(scene.camera(), exact_settings).indirect;
    const auto truth_blocks = block_means(truth, kSize, kSize, kBlock);
    double raw_block2 = 0.0, raw_brightest = 0.0;
    for (uint32_t f = 0; f < kRawFrames; ++f) {
        settings.frame = f;
        const auto raw = renderer.render(scene.camera(), settings).indirect;
        raw_block2 += std::pow(relative_rmse(block_means(raw, kSize, kSize, kBlock), truth_blocks), 2) / kRawFrames;
        raw_brightest = std::max(raw_brightest, brightest(raw));
    }
    settings.denoise = vplkit::DenoiseMode::temporal;
    vplkit::RenderedImage image;
    for (uint32_t f = 0; f < kFrames; ++f) {
        settings.frame = f;
        image = renderer.render(scene.camera(), settings);
    }
    const double mean = sum(image.indirect) / sum(truth);
    const double block = relative_rmse(block_means(image.indirect, kSize, kSize, kBlock), truth_blocks);
    const double target = std::sqrt(raw_block2 / kFrames);
    const double bright = brightest(image.indirect) / brightest(truth);
    MESSAGE("one raw frame: 4x4-block error "
            << std::sqrt(raw_block2) << ", brightest pixel " << raw_brightest / brightest(truth) << "x exact's; "
            << kFrames << " frames accumulated: mean " << mean << " of exact's, block error " << block
            << " (1/sqrt(F) of one frame's: " << target << "), brightest pixel " << bright << "x; the clamp moved "
            << 100.0 * image.firefly_moved_fraction << "% in the last frame");
    CHECK(mean == doctest::Approx(1.0).epsilon(0.01));
    CHECK(block <= 1.5 * target);
    CHECK(bright == doctest::Approx(1.0).epsilon(0.25));
}
