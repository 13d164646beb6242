// The same seed gives the same image (DESIGN.md), for every VPL source and every GI method: two
// renderers, each generating its own VPLs, render the same frames bit for bit.
//
// Before the light-path VPLs were packed by path (trace_vpls.comp appended each at an
// atomicAdd), --vpl-source ir could fail this: the VPLs' order followed the scheduling of the
// driver's threads over the tracer's workgroups (here 4 of them), and the order enters the
// image through the VPL keys' tie-breaks, the tree's floating-point sums and the exact gather's
// sum in buffer order. It can only fail when the threads happen to run in another order, so the
// in-order test in test_vpl_tracing.cpp is the one that fails every time.
//
// The same held for SMC's invalid list (smc_validate.comp appended it by atomics, and revalidation
// draws its entries at random indices, so which VPLs were revalidated followed the scheduling
// once the invalid VPLs spanned several workgroups) and for flc's kept and divergent lists (the
// splats' draw order, hence the rounding of their additive blending): both are now stable
// compactions in index order. The SMC case moves the camera between updates so that hundreds of
// VPLs fall invalid and revalidation has work; flc renders twice per renderer.

#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <string>
#include <utility>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace {

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";

// Small: 32 x 32 pixels, 1024 light paths (4 blocks of the packing), 256 BRSM or SMC VPLs.
vplkit::RenderSettings small_settings(vplkit::VplSource source, vplkit::GiMethod method) {
    vplkit::RenderSettings s;
    s.width = 32;
    s.height = 32;
    s.seed = 11;
    s.method = method;
    s.vpl_source = source;
    s.vpl_paths = 1024;
    s.vpl_bounces = 2;
    s.brsm.vpl_count = 256;
    s.rsm_resolution = 64;
    s.smc.budget = 256;
    s.smc.resample_ratio = 8;
    s.smc.radiosity_samples = 4;
    s.smc_warmup = 2;
    s.samples_per_pixel = 4;
    return s;
}

// The camera turned by `radians` about its up axis (towards its right for a positive angle).
vplkit::scene::Camera turned(vplkit::scene::Camera camera, float radians) {
    const glm::vec3 right = glm::normalize(glm::cross(camera.forward, camera.up));
    camera.forward = glm::normalize(std::cos(radians) * camera.forward + std::sin(radians) * right);
    return camera;
}

}  // namespace

TEST_CASE("vpl determinism: two renderers give bit-identical frames for every VPL source and GI method") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer first(ctx, scene), second(ctx, scene);
    const std::pair<vplkit::VplSource, const char*> sources[] = {
        {vplkit::VplSource::ir, "ir"}, {vplkit::VplSource::brsm, "brsm"}, {vplkit::VplSource::smc, "smc"}};
    for (const auto& [source, source_name] : sources) {
        for (const vplkit::GiMethod method :
             {vplkit::GiMethod::exact, vplkit::GiMethod::sst, vplkit::GiMethod::rtslc, vplkit::GiMethod::hybrid}) {
            const std::string name = std::string(source_name) + " x " + vplkit::gi_method_name(method);
            CAPTURE(name);
            const auto settings = small_settings(source, method);
            const auto a = first.render(scene.camera(), settings);
            const auto b = second.render(scene.camera(), settings);
            REQUIRE(a.vpl_count > 0);
            CHECK(a.vpl_count == b.vpl_count);
            CHECK(a.indirect == b.indirect);
            CHECK(a.radiance == b.radiance);
        }
    }
}

TEST_CASE("vpl determinism: SMC with revalidation over a camera move, and flc, give bit-identical frames") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    SUBCASE("smc") {
        vplkit::Renderer first(ctx, scene), second(ctx, scene);
        auto settings = small_settings(vplkit::VplSource::smc, vplkit::GiMethod::exact);
        settings.smc.budget = 512;  // eight of smc_validate.comp's workgroups, two compaction chunks
        uint32_t invalid = 0, revalidated = 0;
        // Warm-up and a frame at the file's camera, then frames turned away and back: each move
        // leaves many anchors outside the view, so their VPLs are invalid and revalidation draws.
        for (const float angle : {0.0f, 0.6f, -0.3f}) {
            CAPTURE(angle);
            const auto camera = turned(scene.camera(), angle);
            const auto a = first.render(camera, settings);
            const auto b = second.render(camera, settings);
            REQUIRE(a.smc.has_value());
            REQUIRE(b.smc.has_value());
            MESSAGE("smc invalid " << a.smc->invalid << ", revalidated " << a.smc->revalidated << ", vpls "
                                   << a.smc->vpls);
            CHECK(a.smc->invalid == b.smc->invalid);
            CHECK(a.smc->revalidated == b.smc->revalidated);
            CHECK(a.smc->vpls == b.smc->vpls);
            CHECK(a.indirect == b.indirect);
            CHECK(a.radiance == b.radiance);
            if (angle != 0.0f) {
                invalid += a.smc->invalid;
                revalidated += a.smc->revalidated;
            }
        }
        // The moves must have given the list several workgroups' worth of entries and revalidation work.
        CHECK(invalid > 2 * 256);
        CHECK(revalidated > 0);
    }
    SUBCASE("flc") {
        vplkit::Renderer first(ctx, scene), second(ctx, scene);
        const auto settings = small_settings(vplkit::VplSource::ir, vplkit::GiMethod::flc);
        for (const float angle : {0.0f, 0.6f}) {
            CAPTURE(angle);
            const auto camera = turned(scene.camera(), angle);
            const auto a = first.render(camera, settings);
            const auto b = second.render(camera, settings);
            REQUIRE(a.vpl_count > 0);
            CHECK(a.vpl_count == b.vpl_count);
            CHECK(a.indirect == b.indirect);
            CHECK(a.radiance == b.radiance);
        }
    }
}
