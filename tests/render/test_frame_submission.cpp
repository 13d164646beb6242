// A frame from the G-buffer to compose runs as one command buffer (the renderer's
// FrameRecording): VPLs, trees, samplers, upsampling and the denoiser read the counts the GPU
// wrote, and the host reads nothing back before the frame's last pass. Checked through
// PassTiming::submission: every pass up to compose went in one submission; only the output's
// tonemap (after the host's exposure and anti-aliasing mean) comes after. A stage that read a
// count back in between would split the frame, and these checks would fail.

#include "vplkit/context.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <set>
#include <string>

namespace {

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";
constexpr const char* kCornellEmissive = VPLKIT_SOURCE_DIR "/scenes/cornell_emissive/cornell_emissive.gltf";

// The submissions of the frame's passes (every stage but the tonemap), and that some light came
// out of them.
void check_one_submission(const vplkit::RenderedImage& image) {
    std::set<uint64_t> frame;
    std::set<std::string> tags;
    for (const vplkit::PassTiming& t : image.timings) {
        if (t.tag == vplkit::stage_tag(vplkit::FrameStage::tonemap)) continue;
        frame.insert(t.submission);
    }
    CAPTURE(image.plan_summary);
    CHECK(frame.size() == 1);
    CHECK(image.vpl_count > 0);
    double indirect = 0.0;
    for (float v : image.indirect) indirect += v;
    CHECK(indirect > 0.0);
}

vplkit::RenderSettings small(vplkit::GiMethod method, vplkit::VplSource source) {
    vplkit::RenderSettings settings;
    settings.width = 48;
    settings.height = 40;
    settings.method = method;
    settings.vpl_source = source;
    settings.samples_per_pixel = 4;
    settings.vpl_paths = 256;
    settings.brsm.vpl_count = 256;
    return settings;
}

}  // namespace

TEST_CASE("frame submission: hybrid over BRSM VPLs, half-resolution GI and svgf is one command buffer") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    vplkit::RenderSettings settings = small(vplkit::GiMethod::hybrid, vplkit::VplSource::brsm);
    settings.half_resolution_gi = true;
    settings.denoise = vplkit::DenoiseMode::svgf;
    check_one_submission(renderer.render(scene.camera(), settings));
}

TEST_CASE("frame submission: rtslc and sst over IR VPLs (a count below the capacity) are one command buffer") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellEmissive);
    vplkit::Renderer renderer(ctx, scene);
    for (vplkit::GiMethod method : {vplkit::GiMethod::rtslc, vplkit::GiMethod::sst}) {
        const auto image = renderer.render(scene.camera(), small(method, vplkit::VplSource::ir));
        check_one_submission(image);
        CHECK(image.vpl_count < 256u * 2u);  // paths end early: the trees were built past the count
    }
}

TEST_CASE("frame submission: SMC after its warm-up and flc are one command buffer") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    vplkit::RenderSettings settings = small(vplkit::GiMethod::hybrid, vplkit::VplSource::smc);
    settings.smc_warmup = 2;
    settings.smc.budget = 256;
    renderer.render(scene.camera(), settings);  // the warm-up runs in submissions of its own
    settings.frame = 1;
    check_one_submission(renderer.render(scene.camera(), settings));

    check_one_submission(renderer.render(scene.camera(), small(vplkit::GiMethod::flc, vplkit::VplSource::automatic)));
}
