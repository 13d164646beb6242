// stages/svgf.hpp: add_svgf_passes, the denoise passes chained in one call, against the runtime's
// Denoiser (which chains them itself): the same frames, bit for bit, over a moving camera and a
// depth step, for SVGF and for temporal accumulation alone; and its errors.

#include "denoise_setup.hpp"
#include "vplkit/denoiser.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/render_settings.hpp"
#include "vplkit/stages/svgf.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <random>
#include <vector>

namespace {

using namespace vplkit::test;
constexpr uint32_t kSize = 32;

// A closer plane over the columns x >= 16, the back plane elsewhere; noisy radiance on both.
void check_same_as_denoiser(uint32_t atrous_iterations) {
    vplkit::Context& ctx = vplkit::test::context();
    vplkit::Denoiser denoiser = vplkit::Denoiser::create(ctx, kSize, kSize);
    std::vector<vplkit::Image> owned;
    std::vector<vplkit::ImageView> images;
    for (uint32_t i = 0; i < vplkit::stages::kSvgfImageCount; ++i)
        owned.push_back(float4_image(ctx, kSize, kSize, "svgf"));
    for (vplkit::Image& i : owned) images.push_back(i);
    vplkit::stages::DenoiseOptions options;
    options.scene_scale = 10.0f;
    options.atrous_iterations = atrous_iterations;
    const PlaneScene scene{[](int x, int) { return x >= 16 ? -3.0f : -5.0f; },
                           [](int, int) { return glm::vec3(0, 0, 1); }};
    DenoiseImage albedo(kSize, kSize);
    for (auto& t : albedo.texels) t = {0.5, 0.25, 0.75, 1.0};
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> noise(0.0, 2.0);
    glm::mat4 previous(1.0f);
    for (uint32_t frame = 0; frame < 3; ++frame) {
        CAPTURE(frame);
        const glm::mat4 vp = denoise_camera({0.05f * float(frame), 0.0f, 0.0f}, kSize, kSize);
        const DenoiseGeometry geometry = plane_geometry(vp, kSize, kSize, scene);
        DenoiseImage radiance(kSize, kSize);
        for (auto& t : radiance.texels) t = {noise(rng), noise(rng), noise(rng), 0.0};
        vplkit::Image position = upload_image(ctx, geometry.position, "position");
        vplkit::Image normal = upload_image(ctx, geometry.normal, "normal");
        vplkit::Image albedo_image = upload_albedo(ctx, albedo, "albedo");
        vplkit::Image by_denoiser = upload_image(ctx, to_float_precision(radiance), "radiance a");
        vplkit::Image by_chain = upload_image(ctx, to_float_precision(radiance), "radiance b");
        vplkit::stages::GbufferViews gbuffer;
        gbuffer.position = position;
        gbuffer.normal = normal;
        gbuffer.albedo = albedo_image;

        vplkit::PassList a("denoiser");
        denoiser.add_passes(ctx, a, vplkit::DenoiseMode::svgf, gbuffer, by_denoiser, options, false);
        a.run(ctx);
        denoiser.end_frame(vp);
        vplkit::PassList b("svgf chain");
        vplkit::stages::add_svgf_passes(ctx, b, gbuffer, by_chain, images, {frame, vp, previous}, options);
        b.run(ctx);
        previous = vp;

        const DenoiseImage expected = download_image(by_denoiser), got = download_image(by_chain);
        size_t differing = 0;
        for (size_t i = 0; i < got.texels.size(); ++i) differing += got.texels[i] != expected.texels[i];
        CHECK(differing == 0);
    }
}

}  // namespace

TEST_CASE("svgf chain: the runtime Denoiser's frames bit for bit") {
    SUBCASE("svgf") {
        check_same_as_denoiser(5);
    }
    SUBCASE("temporal accumulation alone") {
        check_same_as_denoiser(0);
    }
}

TEST_CASE("svgf chain: a wrong number of images is refused") {
    vplkit::Context& ctx = vplkit::test::context();
    vplkit::Image radiance = float4_image(ctx, kSize, kSize, "radiance");
    std::vector<vplkit::ImageView> images(3, radiance);
    vplkit::PassList passes;
    CHECK_THROWS_WITH_AS(vplkit::stages::add_svgf_passes(ctx, passes, {}, radiance, images, {}, {}),
                         doctest::Contains("3 images given, the chain works in 16"), vplkit::Error);
}
