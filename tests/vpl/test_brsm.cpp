// BRSM VPL generation (shaders/vpl/brsm_*.comp, stages/brsm.hpp) on lavapipe against
// double-precision references (tests/reference/brsm_reference.cpp) and estimator identities.
//
// Scenes: an open box (floor, ceiling, back and side walls; the front open towards the camera)
// with point and spot lights inside, and a floor under a sun. G-buffer 64x48, RSM faces 16 or 32
// texels: small enough for the double references, and every stage's edge cases occur (the cube
// map's face out of the open front is empty; walls meet at creases; texels near the image edge).
//
// Tolerances:
//   contribution  inside the reference's interval (a sample on a pixel edge may round either
//                 way) within 2e-4 of the map's largest value: float sums of 8 terms whose
//                 direction cosines and sines lavapipe evaluates to ~1e-6
//   filter        1e-5 relative: 81 float products and sums
//   importance    1e-5 of the largest value; its mip-chain total 1 within 1e-5
//   VPL flux      flux / (N pmf) within 1e-5 relative (float division); positions exactly the texel's
//   unbiasedness  |mean over n seeds - exact| <= 4 sigma / sqrt(n) + 1e-4 relative (float sums)

#include "brsm_reference.hpp"
#include "geometry_reference.hpp"
#include "raster_test_scenes.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/brsm_buffers.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/stages/importance_warp.hpp"
#include "vplkit/shadow_map.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace {

namespace ref = vplkit::reference;
using vplkit::BrsmOutput;
using vplkit::ShadowMap;
using vplkit::scene::Light;
using vplkit::scene::LightType;
using vplkit::scene::Scene;
using vplkit::stages::BrsmOptions;

constexpr std::array<glm::vec2, 4> kUv = {glm::vec2(0, 0), glm::vec2(0, 1), glm::vec2(1, 1), glm::vec2(1, 0)};

uint32_t add_material(Scene& s, glm::vec3 albedo, float metallic = 0.0f) {
    vplkit::scene::Material m;
    m.name = "material " + std::to_string(s.materials.size());
    m.base_color_factor = glm::vec4(albedo, 1.0f);
    m.metallic_factor = metallic;
    s.materials.push_back(m);
    return uint32_t(s.materials.size() - 1);
}

void finish(Scene& s) {
    s.bounds.min = glm::vec3(INFINITY);
    s.bounds.max = glm::vec3(-INFINITY);
    for (const auto& v : s.vertices) {
        s.bounds.min = glm::min(s.bounds.min, v.position);
        s.bounds.max = glm::max(s.bounds.max, v.position);
    }
}

// The box [-1, 1] x [0, 2] x [-1, 1] without its front (z = 1) face, every face turned inwards,
// coordinates times `scale`; the left wall reddish, the right one greenish, a grey metal-free rest
// (the ceiling half metallic, so (1 - metallic) enters the contribution).
Scene open_box(float scale = 1.0f) {
    Scene s;
    s.source = "brsm test open box";
    const uint32_t grey = add_material(s, {0.7f, 0.7f, 0.7f});
    const uint32_t red = add_material(s, {0.8f, 0.2f, 0.15f});
    const uint32_t green = add_material(s, {0.2f, 0.7f, 0.25f});
    const uint32_t ceiling = add_material(s, {0.6f, 0.6f, 0.6f}, 0.5f);
    auto P = [scale](float x, float y, float z) { return glm::vec3(x, y, z) * scale; };
    raster_test::add_quad(s, {P(-1, 0, -1), P(-1, 0, 1), P(1, 0, 1), P(1, 0, -1)}, kUv, grey);     // floor, up
    raster_test::add_quad(s, {P(-1, 2, -1), P(1, 2, -1), P(1, 2, 1), P(-1, 2, 1)}, kUv, ceiling);  // down
    raster_test::add_quad(s, {P(-1, 0, -1), P(1, 0, -1), P(1, 2, -1), P(-1, 2, -1)}, kUv, grey);   // back, +z
    raster_test::add_quad(s, {P(-1, 0, -1), P(-1, 2, -1), P(-1, 2, 1), P(-1, 0, 1)}, kUv, red);    // left, +x
    raster_test::add_quad(s, {P(1, 0, -1), P(1, 0, 1), P(1, 2, 1), P(1, 2, -1)}, kUv, green);      // right, -x
    finish(s);
    return s;
}

Light point_light(glm::vec3 position, float intensity) {
    Light l;
    l.type = LightType::point;
    l.name = "point";
    l.position = position;
    l.intensity = intensity;
    l.color = {1.0f, 0.9f, 0.8f};
    return l;
}

Light spot_light(glm::vec3 position, glm::vec3 direction, float intensity) {
    Light l;
    l.type = LightType::spot;
    l.name = "spot";
    l.position = position;
    l.direction = glm::normalize(direction);
    l.intensity = intensity;
    l.color = {0.7f, 0.8f, 1.0f};
    l.inner_cone_angle = 0.3f;
    l.outer_cone_angle = 0.6f;
    return l;
}

Light sun(glm::vec3 direction, float intensity) {
    Light l;
    l.type = LightType::directional;
    l.name = "sun";
    l.direction = glm::normalize(direction);
    l.intensity = intensity;
    return l;
}

// A scene drawn into a G-buffer and one RSM per light, ready for the BRSM passes.
class Setup {
public:
    Setup(Scene scene, const vplkit::scene::Camera& camera, uint32_t rsm_resolution, uint32_t width = 64,
          uint32_t height = 48)
        : scene_(std::move(scene)),
          gpu_(vplkit::GpuScene::create(ctx(), scene_)),
          gbuffer_(vplkit::GbufferImages::create(ctx(), width, height)),
          view_(vplkit::camera_view(camera, width, height)),
          scene_scale_(vplkit::build_bvh(vplkit::scene::triangle_positions(scene_)).scene_scale) {
        for (const Light& light : scene_.lights) {
            maps_.push_back(ShadowMap::create(ctx(), light, gpu_.bounds(), rsm_resolution));
        }
        vplkit::PassList passes("brsm test raster");
        vplkit::stages::add_gbuffer_pass(ctx(), passes, gpu_, view_, gbuffer_);
        vplkit::add_shadow_map_passes(ctx(), passes, gpu_, maps_);
        passes.run(ctx());
    }

    static vplkit::Context& ctx() { return vplkit::test::context(); }

    BrsmOutput run(const BrsmOptions& options) {
        BrsmOutput out = BrsmOutput::create(ctx(), maps_, gpu_.bounds(), options);
        vplkit::PassList passes("brsm test");
        vplkit::add_brsm_passes(ctx(), passes, gbuffer_, view_, maps_, scene_scale_, options, out);
        passes.run(ctx());
        return out;
    }

    std::vector<vplkit::shaders::Vpl> vpls(const BrsmOutput& out) {
        const uint32_t count = vplkit::download_brsm_vpl_count(out);
        return count ? out.vpls.download<vplkit::shaders::Vpl>(count) : std::vector<vplkit::shaders::Vpl>{};
    }

    ref::Rsm rsm(size_t light) {
        ShadowMap& m = maps_[light];
        return {read(m.position), read(m.normal), read(m.flux)};
    }
    ref::Gbuffer gbuffer() {
        return {read(gbuffer_.position), read(gbuffer_.normal), read(gbuffer_.geometric_normal), read(gbuffer_.albedo)};
    }
    // Sum of the RSM's flux over its texels, per channel, optionally only where `keep` holds.
    glm::dvec3 rsm_flux_sum(size_t light, const std::vector<float>* importance = nullptr) {
        const ref::Rsm r = rsm(light);
        const uint32_t size = std::bit_ceil(std::max(r.flux.width, r.flux.height));
        glm::dvec3 sum(0.0);
        for (uint32_t y = 0; y < r.flux.height; ++y) {
            for (uint32_t x = 0; x < r.flux.width; ++x) {
                if (r.position.at(x, y).w <= 0.5f) continue;
                if (importance && !((*importance)[size_t(y) * size + x] > 0.0f)) continue;
                sum += glm::dvec3(r.flux.at(x, y));
            }
        }
        return sum;
    }

    const Scene& scene() const { return scene_; }
    const vplkit::stages::CameraView& view() const { return view_; }
    vplkit::GbufferImages& gbuffer_images() { return gbuffer_; }
    float scene_scale() const { return scene_scale_; }
    std::vector<ShadowMap>& maps() { return maps_; }

private:
    static ref::Rgba read(vplkit::Image& image) {
        return {image.width(), image.height(), raster_test::download_rgba(image)};
    }

    Scene scene_;
    vplkit::GpuScene gpu_;
    vplkit::GbufferImages gbuffer_;
    vplkit::stages::CameraView view_;
    float scene_scale_;
    std::vector<ShadowMap> maps_;
};

vplkit::scene::Camera camera(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float scale) {
    auto c = vplkit::scene::look_at(eye * scale, target * scale, up, 0.9f);
    c.znear = 0.01f * scale;
    c.zfar = 100.0f * scale;
    return c;
}

vplkit::scene::Camera box_camera(float scale = 1.0f) {
    return camera({0.3f, 1.1f, 3.2f}, {0.0f, 0.9f, 0.0f}, {0.0f, 1.0f, 0.0f}, scale);
}

Scene box_with(std::vector<Light> lights, float scale = 1.0f) {
    Scene s = open_box(scale);
    for (Light& l : lights) {
        l.position *= scale;
        s.lights.push_back(l);
    }
    return s;
}

std::vector<float> level0(const vplkit::Buffer& mips, uint32_t size) {
    return mips.download<float>(size_t(size) * size);
}

glm::dvec3 total_flux(const std::vector<vplkit::shaders::Vpl>& vpls, size_t first, size_t count) {
    glm::dvec3 sum(0.0);
    for (size_t i = first; i < first + count; ++i) sum += glm::dvec3(vpls[i].flux.x, vpls[i].flux.y, vpls[i].flux.z);
    return sum;
}

// mean over seeds of the total flux of each light's VPLs against `expected`, per channel.
void check_mean_flux(Setup& setup, BrsmOptions options, uint32_t seeds, const std::vector<glm::dvec3>& expected) {
    std::vector<std::vector<glm::dvec3>> totals(expected.size());
    for (uint32_t seed = 0; seed < seeds; ++seed) {
        options.seed = seed;
        const BrsmOutput out = setup.run(options);
        const auto vpls = setup.vpls(out);
        const auto counts = vplkit::download_brsm_light_vpl_counts(out);
        size_t first = 0;
        for (size_t l = 0; l < expected.size(); ++l) {
            totals[l].push_back(total_flux(vpls, first, counts[l]));
            first += counts[l];
        }
        REQUIRE(first == vpls.size());
    }
    for (size_t l = 0; l < expected.size(); ++l) {
        for (int c = 0; c < 3; ++c) {
            double mean = 0, var = 0;
            for (const auto& t : totals[l]) mean += t[c];
            mean /= seeds;
            for (const auto& t : totals[l]) var += (t[c] - mean) * (t[c] - mean);
            const double sigma = std::sqrt(var / (seeds - 1));
            const double bound = 4.0 * sigma / std::sqrt(double(seeds)) + 1e-4 * expected[l][c];
            CAPTURE(l);
            CAPTURE(c);
            CAPTURE(mean);
            CAPTURE(expected[l][c]);
            CAPTURE(sigma);
            CHECK(std::abs(mean - expected[l][c]) <= bound);
        }
    }
}

BrsmOptions small_options(uint32_t vpls) {
    BrsmOptions o;
    o.vpl_count = vpls;
    return o;
}

}  // namespace

TEST_CASE("brsm: contributions and flux luminance match a double reference") {
    Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}), box_camera(), 16);
    const BrsmOptions options = small_options(256);
    const BrsmOutput out = setup.run(options);
    const uint32_t size = out.lights[0].map_size;
    REQUIRE(size == 64);  // a 48 x 32 cube atlas in a 64^2 map
    const auto gpu = out.lights[0].contribution.download<float>(size_t(size) * size);
    const auto gpu_flux = level0(out.lights[0].flux_mips, size);

    ref::ContributionParams p;
    p.camera_view_projection = glm::dmat4(setup.view().view_projection);
    p.map_size = size;
    p.sample_count = options.samples_per_texel;
    p.seed = options.seed;
    p.core_radius = double(options.core_radius) * setup.scene_scale();
    p.max_radius = double(options.max_radius) * setup.scene_scale();
    p.min_distance =
        std::max(1e-2 * setup.scene_scale(), p.core_radius);  // the clamp at the core (brsm_contribution.comp)
    const ref::Rsm rsm = setup.rsm(0);
    const auto expected = ref::brsm_contribution(rsm, setup.gbuffer(), p);
    const auto expected_flux = ref::brsm_flux_luminance(rsm, size);

    double largest = 0;
    for (const auto& e : expected) largest = std::max(largest, e.hi);
    REQUIRE(largest > 0);
    int positive = 0, empty_with_flux = 0, failures = 0;
    for (size_t i = 0; i < gpu.size(); ++i) {
        CAPTURE(i);
        const double g = gpu[i];
        const double nearest = std::clamp(g, expected[i].lo, expected[i].hi);
        const bool ok = std::abs(g - nearest) <= 2e-4 * largest &&
                        std::abs(gpu_flux[i] - expected_flux[i]) <= 1e-5 * expected_flux[i] + 1e-30;
        if (!ok && ++failures <= 5) {
            CAPTURE(g);
            CAPTURE(expected[i].lo);
            CAPTURE(expected[i].hi);
            CAPTURE(gpu_flux[i]);
            CAPTURE(expected_flux[i]);
            CHECK(ok);
        }
        positive += g > 0;
        empty_with_flux += expected_flux[i] > 0 && expected[i].hi == 0;
    }
    CHECK(failures == 0);
    // The estimate is not trivially zero or trivially everywhere: some lit texels see no G-buffer
    // surface their light reaches (e.g. the ceiling right above the light, facing away).
    CHECK(positive > 200);
    MESSAGE("texels with contribution: " << positive << ", lit texels without: " << empty_with_flux);
}

TEST_CASE("brsm: the edge-aware filter matches a double reference") {
    Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}), box_camera(), 16);
    BrsmOptions options = small_options(256);
    for (float max_distance : {0.02f, 0.2f}) {
        for (uint32_t radius : {0u, 2u, 4u}) {
            options.similarity_max_distance = max_distance;
            options.filter_radius = radius;
            options.filter_sigma = 1.0f + 0.5f * float(radius);
            CAPTURE(max_distance);
            CAPTURE(radius);
            const BrsmOutput out = setup.run(options);
            const uint32_t size = out.lights[0].map_size;
            const auto raw = out.lights[0].contribution.download<float>(size_t(size) * size);
            const auto flux = level0(out.lights[0].flux_mips, size);
            const auto gpu = level0(out.lights[0].contribution_mips, size);
            ref::FilterParams p{size, int(radius), options.filter_sigma, options.similarity_min_cos,
                                double(options.similarity_max_distance) * setup.scene_scale()};
            const auto expected = ref::brsm_filter(setup.rsm(0), raw, flux, p);
            int failures = 0, smoothed = 0;
            for (size_t i = 0; i < gpu.size(); ++i) {
                const double g = gpu[i];
                const double nearest = std::clamp(g, expected[i].lo, expected[i].hi);
                failures += std::abs(g - nearest) > 1e-5 * std::abs(nearest) + 1e-30;
                smoothed += raw[i] == 0.0f && g > 0.0f;
            }
            CHECK(failures == 0);
            // radius 0 copies; a wider window gives light to texels whose own estimate was 0.
            if (radius == 0) CHECK(smoothed == 0);
            if (radius == 4) CHECK(smoothed > 0);
        }
    }
}

TEST_CASE("brsm: the importance is the normalized defensive mixture") {
    Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}), box_camera(), 16);
    for (float a : {0.0f, 0.1f, 1.0f}) {
        CAPTURE(a);
        BrsmOptions options = small_options(256);
        options.defensive_fraction = a;
        const BrsmOutput out = setup.run(options);
        const uint32_t size = out.lights[0].map_size;
        const auto filtered = level0(out.lights[0].contribution_mips, size);
        const auto flux = level0(out.lights[0].flux_mips, size);
        const auto chain = out.lights[0].importance_mips.download<float>(vplkit::stages::importance_mip_floats(size));
        const auto expected = ref::brsm_importance(filtered, flux, a);
        const double largest = *std::max_element(expected.begin(), expected.end());
        int failures = 0, zero_flux_positive = 0, lit_zero = 0;
        for (size_t i = 0; i < expected.size(); ++i) {
            failures += std::abs(chain[i] - expected[i]) > 1e-5 * largest;
            zero_flux_positive += flux[i] == 0.0f && chain[i] != 0.0f;
            lit_zero += flux[i] > 0.0f && chain[i] == 0.0f;
        }
        CHECK(failures == 0);
        CHECK(zero_flux_positive == 0);   // never a VPL where no light is
        if (a > 0) CHECK(lit_zero == 0);  // every lit texel can be chosen
        CHECK(std::abs(chain.back() - 1.0) <= 1e-5);
    }
}

namespace {

// Checks every VPL of light 0 against its texel: position, normal, pmf = importance / total and
// flux / (N pmf); returns how many VPLs each quadrant of the map got (x, y halves: 0 1 / 2 3).
std::array<int, 4> check_vpls_are_their_texels(Setup& setup, uint32_t n) {
    std::array<int, 4> quadrants{};
    const BrsmOutput out = setup.run(small_options(n));
    const auto vpls = setup.vpls(out);
    REQUIRE(vpls.size() == n);
    const auto& light = out.lights[0];
    const auto samples = light.samples.download<vplkit::shaders::WarpedSample>(n);
    const auto importance =
        light.importance_mips.download<float>(vplkit::stages::importance_mip_floats(light.map_size));
    const double total = importance.back();
    const ref::Rsm rsm = setup.rsm(0);
    const auto triangles = vplkit::scene::triangle_positions(setup.scene());
    int failures = 0;
    for (uint32_t i = 0; i < n; ++i) {
        CAPTURE(i);
        const auto& v = vpls[i];
        const uint32_t tx = samples[i].texel % light.map_size, ty = samples[i].texel / light.map_size;
        bool ok = tx < rsm.position.width && ty < rsm.position.height;
        if (!ok) {
            CHECK(ok);
            break;
        }
        const glm::vec4 position = rsm.position.at(tx, ty), normal = rsm.normal.at(tx, ty), flux = rsm.flux.at(tx, ty);
        const double pmf = importance[samples[i].texel] / total;
        ok = ok && position.w > 0.5f && std::abs(samples[i].pmf - pmf) <= 1e-5 * pmf;
        ok = ok && v.position.x == position.x && v.position.y == position.y && v.position.z == position.z;
        ok = ok && v.normal.x == normal.x && v.normal.y == normal.y && v.normal.z == normal.z;
        ok = ok && std::abs(glm::length(glm::dvec3(v.normal.x, v.normal.y, v.normal.z)) - 1.0) < 1e-5;
        for (int c = 0; c < 3; ++c) {
            const double expected = flux[c] / (double(n) * samples[i].pmf);
            const double got = c == 0 ? v.flux.x : c == 1 ? v.flux.y : v.flux.z;
            ok = ok && std::isfinite(got) && std::abs(got - expected) <= 1e-5 * expected;
        }
        double nearest = INFINITY;
        const glm::dvec3 p(v.position.x, v.position.y, v.position.z);
        for (size_t k = 0; k < triangles.size(); k += 3) {
            nearest = std::min(nearest,
                               ref::point_triangle_distance(p, glm::dvec3(triangles[k]), glm::dvec3(triangles[k + 1]),
                                                            glm::dvec3(triangles[k + 2])));
        }
        CAPTURE(nearest);
        ok = ok && nearest <= 1e-5 * setup.scene_scale();
        if (!ok && ++failures <= 5) CHECK(ok);
        ++quadrants[(tx < light.map_size / 2 ? 0 : 1) + (ty < light.map_size / 2 ? 0 : 2)];
    }
    CHECK(failures == 0);
    return quadrants;
}

}  // namespace

TEST_CASE("brsm: every VPL is its texel with the texel's flux over N pmf, on a surface") {
    Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}), box_camera(), 16);
    check_vpls_are_their_texels(setup, 500);
}

TEST_CASE("brsm: a square spot-light map with importance in every quadrant: each VPL's pmf is its importance / total") {
    // A point light's padded cube-face map never reaches one quadrant of the importance map, so
    // a pmf wrong there passed every test above; a spot's map is square and, pointing down from
    // under the ceiling with the defensive share, has importance in all four quadrants.
    Setup setup(box_with({spot_light({0.0f, 1.8f, 0.0f}, {0.0f, -1.0f, 0.0f}, 5.0f)}), box_camera(), 16);
    const auto quadrants = check_vpls_are_their_texels(setup, 2000);
    for (int q = 0; q < 4; ++q) {
        CAPTURE(q);
        CHECK(quadrants[q] > 20);  // VPLs land in every quadrant, so every quadrant is checked
    }
}

TEST_CASE("brsm: over seeds the VPLs of each light carry its RSM's reflected flux") {
    // Two lights with their shares; with the defensive term, all of each RSM's flux.
    Setup setup(
        box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f), spot_light({-0.5f, 1.5f, 0.5f}, {0.3f, -1.0f, -0.4f}, 5.0f)}),
        box_camera(), 16);
    check_mean_flux(setup, small_options(400), 24, {setup.rsm_flux_sum(0), setup.rsm_flux_sum(1)});

    // Pure BRSM: the flux of the texels it can choose (positive importance) only.
    BrsmOptions pure = small_options(400);
    pure.defensive_fraction = 0.0f;
    const BrsmOutput probe = setup.run(pure);
    std::vector<glm::dvec3> expected;
    for (size_t l = 0; l < 2; ++l) {
        const auto importance = level0(probe.lights[l].importance_mips, probe.lights[l].map_size);
        expected.push_back(setup.rsm_flux_sum(l, &importance));
        CHECK(expected[l].y < setup.rsm_flux_sum(l).y);  // some lit texels matter to no pixel
    }
    check_mean_flux(setup, pure, 24, expected);
}

TEST_CASE("brsm: scenes at 1e-3 and 1e4 scale keep the flux and stay finite") {
    for (float scale : {1e-3f, 1e4f}) {
        CAPTURE(scale);
        Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}, scale), box_camera(scale), 16);
        check_mean_flux(setup, small_options(300), 12, {setup.rsm_flux_sum(0)});
    }
}

TEST_CASE("brsm: VPLs go where the camera sees their light") {
    // Inside the box, the camera looks into the corner of the left wall and the floor; the light
    // hangs in the middle. (A plane alone would not do: it sends no light to itself.)
    Setup setup(box_with({point_light({0.0f, 1.6f, 0.0f}, 3.0f)}),
                camera({-0.3f, 1.2f, 0.6f}, {-1.0f, 0.3f, -0.3f}, {0.0f, 1.0f, 0.0f}, 1.0f), 32);
    auto near_fraction = [&](float a) {
        BrsmOptions options = small_options(2000);
        options.defensive_fraction = a;
        const auto vpls = setup.vpls(setup.run(options));
        REQUIRE(vpls.size() == 2000);
        size_t near = 0;
        for (const auto& v : vpls) near += v.position.x < -0.2f;
        return double(near) / double(vpls.size());
    };
    const double brsm = near_fraction(0.1f), pure = near_fraction(0.0f), flux_only = near_fraction(1.0f);
    MESSAGE("VPLs at x < -0.2: " << brsm << " (a = 0.1), " << pure << " (a = 0), " << flux_only
                                 << " (a = 1, flux only)");
    CHECK(pure > flux_only + 0.3);
    CHECK(brsm > flux_only + 0.25);
    CHECK(pure >= brsm);
}

TEST_CASE("brsm: a light whose map has no surface places no VPLs and says so") {
    // The spot points out of the open front: its RSM is empty, its importance all zero.
    Setup setup(
        box_with({spot_light({0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, 5.0f), point_light({0.2f, 1.7f, -0.3f}, 3.0f)}),
        box_camera(), 16);
    const BrsmOutput out = setup.run(small_options(300));
    const auto counts = vplkit::download_brsm_light_vpl_counts(out);
    REQUIRE(counts.size() == 2);
    CHECK(counts[0] == 0);
    CHECK(counts[1] == out.lights[1].vpl_share);
    CHECK(out.lights[0].vpl_share > 0);
    const auto vpls = setup.vpls(out);
    CHECK(vpls.size() == counts[1]);  // the point light's VPLs follow directly, no gap
    for (const auto& v : vpls) CHECK((std::isfinite(v.flux.x) && v.flux.x > 0.0f));
}

TEST_CASE("brsm: the same seed gives the same VPLs and another seed other ones") {
    Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}), box_camera(), 16);
    BrsmOptions options = small_options(300);
    options.seed = 7;
    const auto a = setup.vpls(setup.run(options));
    const auto b = setup.vpls(setup.run(options));
    options.seed = 8;
    const auto c = setup.vpls(setup.run(options));
    REQUIRE(a.size() == b.size());
    REQUIRE(a.size() == c.size());
    auto same = [](const auto& x, const auto& y) {
        return std::equal(x.begin(), x.end(), y.begin(), [](const auto& p, const auto& q) {
            return p.position.x == q.position.x && p.position.y == q.position.y && p.position.z == q.position.z &&
                   p.flux.x == q.flux.x;
        });
    };
    CHECK(same(a, b));
    CHECK(!same(a, c));
}

TEST_CASE("brsm: light by light gives the same VPLs as all lights at once") {
    Setup setup(
        box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f), spot_light({-0.5f, 1.5f, 0.5f}, {0.3f, -1.0f, -0.4f}, 5.0f)}),
        box_camera(), 16);
    BrsmOptions options = small_options(300);
    options.seed = 5;
    const auto together = setup.vpls(setup.run(options));

    vplkit::Context& ctx = Setup::ctx();
    auto out = BrsmOutput::create_for_lights(ctx, setup.scene().lights, setup.scene().bounds, options);
    REQUIRE(out.lights.size() == 2);
    for (size_t i = 0; i < 2; ++i) {
        ShadowMap& map = setup.maps()[i];
        vplkit::allocate_brsm_light_buffers(ctx, map, out.lights[i]);
        vplkit::PassList passes("brsm light by light");
        if (i == 0) vplkit::stages::add_brsm_count_clear_pass(passes, out);
        vplkit::stages::add_brsm_light_passes(ctx, passes, setup.gbuffer_images(), setup.view(), map, i,
                                              setup.scene_scale(), options, out);
        passes.run(ctx);
        CHECK(vplkit::download_brsm_light_vpl_count(out, i) == out.lights[i].vpl_share);
        out.lights[i] = vplkit::BrsmLightBuffers{0, out.lights[i].vpl_share};
        CHECK_THROWS_AS(vplkit::download_brsm_light_vpl_count(out, i), vplkit::Error);  // released
    }
    const auto apart = setup.vpls(out);
    REQUIRE(apart.size() == together.size());
    for (size_t i = 0; i < apart.size(); ++i) {
        CAPTURE(i);
        CHECK(apart[i].position.x == together[i].position.x);
        CHECK(apart[i].flux.y == together[i].flux.y);
    }
}

TEST_CASE("brsm: the VPL budget follows light power") {
    vplkit::scene::Bounds bounds{{-1.0f, 0.0f, -1.0f}, {1.0f, 2.0f, 1.0f}};
    Light dim = point_light({0, 1, 0}, 1.0f), bright = point_light({0, 1, 0}, 3.0f), off = point_light({0, 1, 0}, 0.0f);
    auto shares = vplkit::brsm_vpl_shares(std::vector<Light>{dim, off, bright}, bounds, 1000);
    CHECK(shares == std::vector<uint32_t>{250, 0, 750});
    shares = vplkit::brsm_vpl_shares(std::vector<Light>{dim, bright, bright}, bounds, 10);
    CHECK(shares[0] + shares[1] + shares[2] == 10);
    CHECK(shares[0] >= 1);
    // A very dim light still gets one VPL: none would lose its light from the image.
    Light faint = point_light({0, 1, 0}, 1e-6f);
    shares = vplkit::brsm_vpl_shares(std::vector<Light>{faint, bright}, bounds, 100);
    CHECK(shares == std::vector<uint32_t>{1, 99});
    // A sun's power is its irradiance over the scene's bounding disc.
    Light s = sun({0, -1, 0}, 1.0f);
    s.color = glm::vec3(1.0f);
    Light p = point_light({0, 1, 0}, 1.0f);
    p.color = glm::vec3(1.0f);
    const double disc = std::numbers::pi * 3.0;  // radius^2 = (|(2, 2, 2)| / 2)^2 = 3
    shares = vplkit::brsm_vpl_shares(std::vector<Light>{s, p}, bounds, 100000);
    CHECK(std::abs(shares[0] / 100000.0 - disc / (disc + 4.0 * std::numbers::pi)) < 1e-4);
    CHECK_THROWS_AS(vplkit::brsm_vpl_shares(std::vector<Light>{off}, bounds, 10), vplkit::Error);
    CHECK_THROWS_AS(vplkit::brsm_vpl_shares(std::vector<Light>{dim, bright}, bounds, 1), vplkit::Error);
}

TEST_CASE("brsm: invalid options are refused") {
    auto refused = [](auto change) {
        BrsmOptions o;
        change(o);
        CHECK_THROWS_AS(vplkit::stages::validate(o), vplkit::Error);
    };
    refused([](BrsmOptions& o) { o.vpl_count = 0; });
    refused([](BrsmOptions& o) { o.samples_per_texel = 0; });
    refused([](BrsmOptions& o) { o.samples_per_texel = 5000; });
    refused([](BrsmOptions& o) { o.core_radius = 0.0f; });
    refused([](BrsmOptions& o) { o.core_radius = NAN; });
    refused([](BrsmOptions& o) { o.max_radius = o.core_radius; });
    refused([](BrsmOptions& o) { o.filter_sigma = -1.0f; });
    refused([](BrsmOptions& o) { o.filter_radius = 9; });
    refused([](BrsmOptions& o) { o.similarity_min_cos = 1.0f; });
    refused([](BrsmOptions& o) { o.similarity_max_distance = 0.0f; });
    refused([](BrsmOptions& o) { o.defensive_fraction = 1.5f; });
    refused([](BrsmOptions& o) { o.defensive_fraction = -0.1f; });
    CHECK_NOTHROW(vplkit::stages::validate(BrsmOptions{}));
    CHECK_THROWS_AS(BrsmOutput::create(vplkit::test::context(), {}, vplkit::scene::Bounds{}, BrsmOptions{}),
                    vplkit::Error);
}
