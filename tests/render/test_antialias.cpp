// Anti-aliasing by jittered, accumulated frames (vplkit/antialias.hpp; RenderSettings::antialias):
// - the jitter: 0 for frame 0, then the Halton(2,3) points less 0.5, all inside the pixel;
// - jittered_view moves a projected point by the offset in pixels, near and far alike;
// - on the in-repo Cornell box (direct light, 48 x 40): frame 0 is the frame without it, bit for
//   bit; over 8 frames the pixels on a contrast edge take values between their two sides while
//   flat regions keep theirs and the image keeps its light; without it 8 frames are the first;
// - with temporal denoising the jitter is not motion: the filter's history survives it, so 8
//   accumulated frames of hybrid's indirect light stay well below one raw frame's error.

#include "vplkit/antialias.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/context.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace {

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";

std::vector<double> luminance(const std::vector<float>& rgb) {
    std::vector<double> y;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3)
        y.push_back(0.2126 * rgb[i] + 0.7152 * rgb[i + 1] + 0.0722 * rgb[i + 2]);
    return y;
}

// Pixel coordinates (x right, y down) of a world point.
glm::dvec2 pixel_of(const glm::mat4& view_projection, glm::vec3 p, uint32_t w, uint32_t h) {
    const glm::vec4 clip = view_projection * glm::vec4(p, 1.0f);
    return {(double(clip.x) / clip.w * 0.5 + 0.5) * w, (double(clip.y) / clip.w * 0.5 + 0.5) * h};
}

// sqrt(mean((a - b)^2)) / mean(b) over K x K block means (edges, where the jitter moves the
// surface, are averaged with their neighbourhood).
double block_relative_rmse(const std::vector<float>& image, const std::vector<float>& truth, uint32_t w, uint32_t h) {
    constexpr uint32_t k = 4;
    double e = 0.0, t = 0.0;
    size_t n = 0;
    for (uint32_t by = 0; by + k <= h; by += k)
        for (uint32_t bx = 0; bx + k <= w; bx += k)
            for (int c = 0; c < 3; ++c) {
                double a = 0.0, b = 0.0;
                for (uint32_t y = by; y < by + k; ++y)
                    for (uint32_t x = bx; x < bx + k; ++x) {
                        a += image[(size_t(y) * w + x) * 3 + c];
                        b += truth[(size_t(y) * w + x) * 3 + c];
                    }
                e += (a - b) * (a - b);
                t += b;
                ++n;
            }
    return std::sqrt(e / n) / (t / n);
}

}  // namespace

TEST_CASE("antialias: frame 0 at the pixel centre, then Halton(2,3) less 0.5, all inside the pixel") {
    CHECK(vplkit::subpixel_jitter(0) == glm::vec2(0.0f));
    const std::pair<float, float> first[] = {
        {0.5f, 1.0f / 3}, {0.25f, 2.0f / 3}, {0.75f, 1.0f / 9}, {0.125f, 4.0f / 9}};
    for (uint32_t f = 1; f <= 4; ++f) {
        CHECK(vplkit::subpixel_jitter(f).x == doctest::Approx(first[f - 1].first - 0.5f));
        CHECK(vplkit::subpixel_jitter(f).y == doctest::Approx(first[f - 1].second - 0.5f));
    }
    std::set<std::pair<float, float>> seen;
    glm::dvec2 mean(0.0);
    for (uint32_t f = 0; f < 16; ++f) {
        const glm::vec2 j = vplkit::subpixel_jitter(f);
        CHECK(j.x >= -0.5f);
        CHECK(j.x < 0.5f);
        CHECK(j.y >= -0.5f);
        CHECK(j.y < 0.5f);
        seen.insert({j.x, j.y});
        mean += glm::dvec2(j) / 16.0;
    }
    CHECK(seen.size() == 16);
    CHECK(std::abs(mean.x) < 0.05);
    CHECK(std::abs(mean.y) < 0.05);
}

TEST_CASE("antialias: jittered_view moves a projected point by the offset in pixels, near and far") {
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    const uint32_t w = 64, h = 48;
    const auto view = vplkit::camera_view(scene.camera(), w, h);
    const glm::vec2 offset(0.25f, -0.375f);
    const auto moved = vplkit::jittered_view(view, offset, w, h);
    const vplkit::scene::Camera& c = scene.camera();
    for (float distance : {0.5f, 2.0f, 8.0f}) {
        const glm::vec3 p = c.position + distance * c.forward + 0.1f * c.up;
        const glm::dvec2 shift = pixel_of(moved.view_projection, p, w, h) - pixel_of(view.view_projection, p, w, h);
        CHECK(shift.x == doctest::Approx(offset.x).epsilon(1e-3));
        CHECK(shift.y == doctest::Approx(offset.y).epsilon(1e-3));
    }
    CHECK(moved.position == view.position);
}

TEST_CASE("antialias render: over 8 frames a contrast edge takes in-between values, flat regions keep theirs") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    vplkit::RenderSettings settings;
    settings.width = 48;
    settings.height = 40;
    const uint32_t w = settings.width, h = settings.height;
    const auto centre = renderer.render(scene.camera(), settings);
    const std::vector<double> y0 = luminance(centre.radiance);

    settings.antialias = true;
    vplkit::RenderedImage image;
    for (uint32_t f = 0; f < 8; ++f) {
        settings.frame = f;
        image = renderer.render(scene.camera(), settings);
        if (f == 0) CHECK(image.radiance == centre.radiance);  // frame 0: the pixel centres
    }
    const std::vector<double> y = luminance(image.radiance);
    // Edge pixels: in the centre frame, lit beside a pixel that gets no light at all (a shadow's or
    // the box's silhouette against the dark outside), or the reverse. A pixel crossed by the edge in
    // some of the jittered frames moves towards the other side; one whose edge lies on its border
    // (the box's vertical sides) keeps its value. Flat: every neighbour within 5%.
    double mean0 = 0.0;
    for (double v : y0) mean0 += v / double(y0.size());
    size_t edges = 0, between = 0, flat = 0, flat_kept = 0;
    double light = 0.0, light0 = 0.0;  // clamped to the mean: the light's 1/d^2 peak moves with the jitter
    for (uint32_t py = 1; py + 1 < h; ++py)
        for (uint32_t px = 1; px + 1 < w; ++px) {
            const size_t i = size_t(py) * w + px;
            light += std::min(y[i], mean0);
            light0 += std::min(y0[i], mean0);
            double lo = y0[i], hi = y0[i];
            for (size_t n : {i - 1, i + 1, i - w, i + w}) lo = std::min(lo, y0[n]), hi = std::max(hi, y0[n]);
            if (lo == 0.0 && hi > 0.5 * mean0) {
                ++edges;
                const double far = y0[i] == 0.0 ? hi : 0.0;
                if (std::abs(y[i] - y0[i]) > 0.05 * hi && (y[i] - y0[i]) * (far - y0[i]) > 0.0) ++between;
            } else if (hi <= 1.05 * lo) {
                ++flat;
                if (std::abs(y[i] - y0[i]) <= 0.02 * y0[i] + 1e-6) ++flat_kept;
            }
        }
    MESSAGE(edges << " edge pixels, " << between << " moved towards the other side; " << flat << " flat pixels, "
                  << flat_kept << " within 2%; clamped light " << light / light0);
    REQUIRE(edges > 40);
    CHECK(between >= edges / 6);  // measured 33 of 132 (without anti-aliasing: 0)
    CHECK(flat_kept >= flat * 9 / 10);
    CHECK(light / light0 == doctest::Approx(1.0).epsilon(0.02));

    // Without it, 8 frames are the first one.
    settings.antialias = false;
    for (uint32_t f = 0; f < 8; ++f) {
        settings.frame = f;
        image = renderer.render(scene.camera(), settings);
    }
    CHECK(image.radiance == centre.radiance);
}

TEST_CASE("antialias render: with temporal denoising the jitter is not motion (the history is kept)") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    vplkit::RenderSettings settings;
    settings.width = 48;
    settings.height = 40;
    settings.method = vplkit::GiMethod::exact;
    settings.vpl_source = vplkit::VplSource::brsm;
    settings.brsm.vpl_count = 512;
    settings.rsm_resolution = 128;
    const auto truth = renderer.render(scene.camera(), settings).indirect;
    settings.method = vplkit::GiMethod::hybrid;
    settings.samples_per_pixel = 2;
    const auto raw = renderer.render(scene.camera(), settings).indirect;
    settings.denoise = vplkit::DenoiseMode::temporal;
    settings.denoise_options.firefly_k_sigma = 0.0f;
    settings.antialias = true;
    std::vector<float> accumulated;
    for (uint32_t f = 0; f < 8; ++f) {
        settings.frame = f;
        accumulated = renderer.render(scene.camera(), settings).indirect;
    }
    const double raw_error = block_relative_rmse(raw, truth, settings.width, settings.height);
    const double error = block_relative_rmse(accumulated, truth, settings.width, settings.height);
    MESSAGE("relative RMSE of 4x4 block means against exact: one raw frame "
            << raw_error << ", 8 jittered frames accumulated " << error);
    // A history dropped every frame would leave the raw frame's error; 8 frames kept: ~1/sqrt(8).
    CHECK(error < 0.6 * raw_error);
}
