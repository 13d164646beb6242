// Energy: a method that is biased by design may blur light, never lose or add it (DESIGN.md,
// Tests). Whole frames with visibility on, image totals of indirect light:
//
// - The analytic case: a point light at the centre of a closed diffuse sphere of albedo rho
//   (scenes/enclosure_sphere, see scenes/make_enclosure.py), where one-bounce indirect / direct =
//   rho at every pixel. `exact` against rho, every sampling method against `exact`.
// - Cornell boxes (the in-repo one, and McGuire's CornellBox-Original with a point light when
//   ../shared/scenes is beside the repository) against `exact` over the same VPLs: instant
//   radiosity and BRSM VPLs, full and half GI resolution, several samples per pixel.
//
// What these tests caught (lavapipe; ratios of image totals to exact over the same VPLs). Before
// the shadow ray of a substitute went to a real VPL of its node (sst_sampling.glsl,
// sst_shadow_target): sphere sst 0.63, hybrid 0.64 (rays to substitute positions drawn on a
// curved cluster's plane end behind the sphere's wall); CornellBox-Original sst 0.954, hybrid
// 0.953 (positions inside the blocks). After: sphere 0.98-0.99, Cornell boxes 0.99-1.01.
// Measured with `vplkit render --scene scenes/enclosure_sphere/enclosure_sphere.gltf --width 64
// --height 64 --vpl-source ir --bounces 1 --vpls 2048 --method M --spp 16 --out-direct d.pfm
// --out-indirect i.pfm` and the ratio of the two images' means.

// Tolerances. Each frame's total is a mean over thousands of pixels, each over several samples;
// the ratios' seed-to-seed spread is printed (MESSAGE). The mean over the seeds must lie within
// 3% of exact: sst's and hybrid's remaining bias is the blur of a substitute (its position,
// normal and distance stand for its VPLs'), which moves light between pixels but keeps the total
// to about 1% (measured above), and 3% leaves room for the noise of 4 seeds (one seed's sd
// ~1-2%) and other drivers. Half resolution adds the upsampling's own spread (<1% here). `exact`
// against rho: 2%, for the facets of the sphere mesh, the glTF BRDF's specular term at roughness
// 1 (direct light arrives near normal incidence, indirect from every direction) and the 1/d^2
// clamp (measured 0.5013 for rho 0.5).

#include "vplkit/context.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace {

constexpr const char* kEnclosure = VPLKIT_SOURCE_DIR "/scenes/enclosure_sphere/enclosure_sphere.gltf";
constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";
constexpr const char* kCornellShared = VPLKIT_SOURCE_DIR "/../shared/scenes/CornellBox/CornellBox.gltf";
constexpr double kAlbedo = 0.5;  // scenes/make_enclosure.py
constexpr int kSeeds = 8;
constexpr double kTolerance = 0.03;

double total(const std::vector<float>& values) {
    double sum = 0.0;
    for (float v : values) sum += v;
    return sum;
}

// One sampled configuration: a method, its samples per pixel, GI resolution.
struct Variant {
    vplkit::GiMethod method;
    uint32_t spp;
    bool half;
    std::string name() const {
        return std::string(vplkit::gi_method_name(method)) + " " + std::to_string(spp) + " spp" + (half ? " half" : "");
    }
};

struct RatioStats {
    double sum = 0.0, sum_sq = 0.0;
    int n = 0;
    void add(double r) {
        sum += r;
        sum_sq += r * r;
        ++n;
    }
    double mean() const { return sum / n; }
    double sd() const { return n > 1 ? std::sqrt(std::max(0.0, (sum_sq - n * mean() * mean()) / (n - 1))) : 0.0; }
};

// Renders `exact` and every variant for kSeeds seeds (each seed's own VPL set, shared by all of
// that seed's frames) and checks each variant's mean ratio of indirect totals to exact's at the
// same GI resolution (half-resolution variants against exact at half resolution: the same
// downsampling and upsampling, so the ratio is the method's; the upsampling's own effect is
// checked by the half-resolution case below). Returns exact's mean ratio of indirect to direct.
double check_against_exact(const vplkit::scene::Scene& scene, vplkit::RenderSettings base,
                           const std::vector<Variant>& variants) {
    vplkit::Renderer renderer(vplkit::test::context(), scene);
    std::vector<RatioStats> stats(variants.size());
    RatioStats exact_over_direct;
    for (int seed = 0; seed < kSeeds; ++seed) {
        auto settings = base;
        settings.seed = uint32_t(seed);
        settings.method = vplkit::GiMethod::exact;
        const auto exact = renderer.render(scene.camera(), settings);
        settings.half_resolution_gi = true;
        const double exact_total[2] = {total(exact.indirect),
                                       total(renderer.render(scene.camera(), settings).indirect)};
        REQUIRE(exact_total[0] > 0.0);
        REQUIRE(exact_total[1] > 0.0);
        exact_over_direct.add(exact_total[0] / total(exact.direct));
        for (size_t v = 0; v < variants.size(); ++v) {
            settings.method = variants[v].method;
            settings.samples_per_pixel = variants[v].spp;
            settings.half_resolution_gi = variants[v].half;
            const auto frame = renderer.render(scene.camera(), settings);
            CHECK(frame.vpl_count == exact.vpl_count);  // the same VPL set
            CHECK(frame.non_finite_pixels == 0);
            stats[v].add(total(frame.indirect) / exact_total[variants[v].half ? 1 : 0]);
        }
    }
    for (size_t v = 0; v < variants.size(); ++v) {
        const std::string name = variants[v].name();
        MESSAGE(scene.source.filename().string() << ": " << name << ": mean indirect / exact " << stats[v].mean()
                                                 << " over " << kSeeds << " seeds, sd " << stats[v].sd());
        CAPTURE(name);
        CHECK(stats[v].mean() == doctest::Approx(1.0).epsilon(kTolerance));
    }
    return exact_over_direct.mean();
}

vplkit::RenderSettings one_bounce(vplkit::VplSource source, uint32_t width, uint32_t height, uint32_t vpls) {
    vplkit::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.vpl_source = source;
    settings.vpl_bounces = 1;
    settings.vpl_paths = vpls;
    settings.brsm.vpl_count = vpls;
    settings.rsm_resolution = 128;
    settings.direct_samples = 4;
    settings.block_size = 8;
    return settings;
}

const std::vector<Variant> kVariants = {
    {vplkit::GiMethod::sst, 4, false},     {vplkit::GiMethod::sst, 16, false},   {vplkit::GiMethod::hybrid, 4, false},
    {vplkit::GiMethod::hybrid, 16, false}, {vplkit::GiMethod::hybrid, 32, true}, {vplkit::GiMethod::rtslc, 8, false},
};

}  // namespace

TEST_CASE("energy: inside a closed diffuse sphere one-bounce indirect / direct = albedo, for every method") {
    const auto scene = vplkit::scene::load_gltf(kEnclosure);
    const auto settings = one_bounce(vplkit::VplSource::ir, 40, 40, 1024);
    const double exact_ratio = check_against_exact(scene, settings, kVariants);
    MESSAGE("exact: indirect / direct " << exact_ratio << " (albedo " << kAlbedo << ")");
    CHECK(exact_ratio == doctest::Approx(kAlbedo).epsilon(0.02));
}

TEST_CASE("energy: the in-repo Cornell box, IR and BRSM VPLs, full and half resolution, against exact") {
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    for (const auto source : {vplkit::VplSource::ir, vplkit::VplSource::brsm}) {
        CAPTURE(int(source));
        check_against_exact(scene, one_bounce(source, 64, 64, 1024), kVariants);
    }
}

TEST_CASE("energy: CornellBox-Original with a point light (blocks on the floor), against exact") {
    if (!std::filesystem::exists(kCornellShared)) {
        MESSAGE("skipped: " << kCornellShared << " not found (../shared/scenes is not beside the repository)");
        return;
    }
    auto scene = vplkit::scene::load_gltf(kCornellShared);
    scene.lights.push_back(vplkit::scene::parse_point("0,1.5,0,1,1,1,4"));
    check_against_exact(scene, one_bounce(vplkit::VplSource::ir, 64, 64, 2048), kVariants);
}

TEST_CASE("energy: half-resolution GI keeps full resolution's light (exact, 128 x 128)") {
    // Downsampling the G-buffer and upsampling the light move light between pixels; the total
    // must stay. At 64 x 64 the 32 x 32 G-buffer misses whole features (CornellBox-Original from
    // its file camera: exact at half resolution 4.5% low), which is why the cases above compare
    // half-resolution methods with exact at half resolution; at 128 x 128 it is within 0.4%
    // (measured). Tolerance 2%: one seed, 1024 paths, and the upsampling's edge fallbacks.
    std::vector<vplkit::scene::Scene> scenes;
    scenes.push_back(vplkit::scene::load_gltf(kCornellPoint));
    scenes.push_back(vplkit::scene::load_gltf(kEnclosure));
    if (std::filesystem::exists(kCornellShared)) {
        scenes.push_back(vplkit::scene::load_gltf(kCornellShared));
        scenes.back().lights.push_back(vplkit::scene::parse_point("0,1.5,0,1,1,1,4"));
    }
    for (const auto& scene : scenes) {
        vplkit::Renderer renderer(vplkit::test::context(), scene);
        auto settings = one_bounce(vplkit::VplSource::ir, 128, 128, 1024);
        settings.direct_samples = 1;
        settings.method = vplkit::GiMethod::exact;
        const double full = total(renderer.render(scene.camera(), settings).indirect);
        settings.half_resolution_gi = true;
        const double half = total(renderer.render(scene.camera(), settings).indirect);
        const std::string name = scene.source.filename().string();
        MESSAGE(name << ": exact at half resolution / full " << half / full);
        CAPTURE(name);
        CHECK(half / full == doctest::Approx(1.0).epsilon(0.02));
    }
}
