// The svgf chain (add_svgf_passes at the kit's default options) on heavy-tailed noise: a flat
// plane of constant irradiance whose per-pixel samples are mostly 1 and rarely (2%) 50, so half
// the light comes in rare outliers, as hybrid's few-sample gathers deliver it. Over 4 static
// frames the filtered image must keep the light of its input. With SVGF's own luminance weight
// (the centre pixel's variance, normalized by the centre's weight sum) an outlier pulled itself
// down while its dark neighbours shut it out: the output held 0.901 of the input's light (0.765
// without the firefly clamp); samples/dropin lost 13-14% so.
// Tolerances: the chain (demodulation, running mean, energy-preserving clamp, a-trous) keeps the
// sum exactly but for float rounding, so output / input within 0.5%; against the true mean the
// input itself errs by its sampling error, 3.46 / sqrt(4 x 4096) = 2.7% (one sigma), so the output
// is held to 3 sigma of the truth; and the noise must fall (a filter that did nothing would keep
// the light too).

#include "denoise_setup.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/svgf.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace vplkit;
using namespace vplkit::test;

namespace {

void check_light_kept(float firefly_k_sigma) {
    constexpr uint32_t kSize = 64, kFrames = 4;
    constexpr double kOutlierChance = 0.02, kOutlier = 50.0, kAlbedo = 0.5;
    const double truth = kAlbedo * ((1.0 - kOutlierChance) + kOutlierChance * kOutlier);
    Context& ctx = context();
    std::vector<Image> owned;
    std::vector<ImageView> images;
    for (uint32_t i = 0; i < stages::kSvgfImageCount; ++i) owned.push_back(float4_image(ctx, kSize, kSize, "svgf"));
    for (Image& i : owned) images.push_back(i);
    stages::DenoiseOptions options;
    options.scene_scale = 10.0f;
    options.firefly_k_sigma = firefly_k_sigma;
    const glm::mat4 vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const DenoiseGeometry geometry =
        plane_geometry(vp, kSize, kSize, {[](int, int) { return -5.0f; }, [](int, int) { return glm::vec3(0, 0, 1); }});
    DenoiseImage albedo(kSize, kSize);
    for (auto& t : albedo.texels) t = {kAlbedo, kAlbedo, kAlbedo, 1.0};
    Image position = upload_image(ctx, geometry.position, "position");
    Image normal = upload_image(ctx, geometry.normal, "normal");
    Image albedo_image = upload_albedo(ctx, albedo, "albedo");
    stages::GbufferViews gbuffer;
    gbuffer.position = position;
    gbuffer.normal = normal;
    gbuffer.albedo = albedo_image;

    std::mt19937 rng(7);
    std::bernoulli_distribution outlier(kOutlierChance);
    const size_t pixels = size_t(kSize) * kSize;
    std::vector<double> raw_mean(pixels, 0.0);  // each pixel's mean over the frames
    DenoiseImage filtered(kSize, kSize);
    for (uint32_t frame = 0; frame < kFrames; ++frame) {
        DenoiseImage radiance(kSize, kSize);
        for (size_t i = 0; i < pixels; ++i) {
            const double l = kAlbedo * (outlier(rng) ? kOutlier : 1.0);
            radiance.texels[i] = {l, l, l, 0.0};
            raw_mean[i] += l / kFrames;
        }
        Image image = upload_image(ctx, radiance, "radiance");
        PassList passes("svgf energy");
        stages::add_svgf_passes(ctx, passes, gbuffer, image, images, {frame, vp, vp}, options);
        passes.run(ctx);
        filtered = download_image(image);
    }
    double input = 0.0, output = 0.0, raw_error = 0.0, filtered_error = 0.0;
    for (size_t i = 0; i < pixels; ++i) {
        input += raw_mean[i] / pixels;
        output += filtered.texels[i][0] / pixels;
        raw_error += (raw_mean[i] - truth) * (raw_mean[i] - truth) / pixels;
        filtered_error += (filtered.texels[i][0] - truth) * (filtered.texels[i][0] - truth) / pixels;
    }
    raw_error = std::sqrt(raw_error) / truth;
    filtered_error = std::sqrt(filtered_error) / truth;
    MESSAGE("svgf on heavy-tailed noise: output / input mean "
            << output / input << ", input / truth " << input / truth << ", output / truth " << output / truth
            << "; relative RMSE " << raw_error << " raw, " << filtered_error << " filtered");
    CHECK(output / input == doctest::Approx(1.0).epsilon(0.005));
    CHECK(output / truth == doctest::Approx(1.0).epsilon(3.0 * 0.027));
    CHECK(filtered_error < 0.25 * raw_error);
}

}  // namespace

TEST_CASE("svgf chain: heavy-tailed noise keeps its light") {
    SUBCASE("the kit's default options (firefly clamp at 4 sigma)") {
        check_light_kept(4.0f);
    }
    SUBCASE("no firefly clamp") {
        check_light_kept(0.0f);
    }
}
