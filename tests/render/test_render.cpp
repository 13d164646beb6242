// The whole frame. Direct light (G-buffer raster, direct light, tonemap) on the in-repo Cornell
// box, checked pixel by pixel against a CPU path through the same scene written independently:
// a camera ray through the pixel centre (double precision, brute force over all triangles), the
// material at the hit, the glTF BRDF and a brute-force shadow ray.
// Tolerance: relative 2e-3 per channel: the G-buffer stores albedo in half floats (2^-11) and
// rasterizes interpolated positions (float); the BRDF and attenuation agree to 1e-4 (see
// tests/lighting). Pixels whose camera ray or shadow ray passes within 1e-3 (barycentric units) of
// a triangle edge are skipped: there rasterization rules or float vs double may pick either side.

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/stages/upsample.hpp"
#include "vplkit_test/context.hpp"
#include "direct_light_reference.hpp"
#include "ray_reference.hpp"

#include <doctest/doctest.h>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace {

using vplkit::reference::Vec3;

std::vector<vplkit::reference::Triangle> reference_triangles(const vplkit::scene::Scene& scene) {
    std::vector<vplkit::reference::Triangle> out;
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
        vplkit::reference::Triangle tri;
        Vec3* corners[3] = {&tri.v0, &tri.v1, &tri.v2};
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = scene.vertices[scene.indices[3 * t + k]].position;
            *corners[k] = {p.x, p.y, p.z};
        }
        out.push_back(tri);
    }
    return out;
}

// Smallest |margin| of any triangle the ray meets within its interval (edge proximity).
double edge_margin(const std::vector<vplkit::reference::Triangle>& triangles, const vplkit::reference::Ray& ray) {
    double margin = INFINITY;
    for (const auto& t : triangles) {
        auto hit = vplkit::reference::intersect(ray, t);
        if (hit && hit->t > ray.tmin && hit->t < ray.tmax) margin = std::min(margin, std::abs(hit->margin));
    }
    return margin;
}

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";

// A tiny frame with exact indirect light: what the indirect-light cases render.
vplkit::RenderSettings small_exact_settings(uint32_t width = 24, uint32_t height = 20) {
    vplkit::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.method = vplkit::GiMethod::exact;
    return settings;
}

// Checks that the composed radiance is direct + indirect, exactly (one float addition), with
// non-negative indirect light; returns how many channels have indirect light and no direct light.
size_t check_parts_add_up(const vplkit::RenderedImage& image) {
    size_t indirect_only = 0;
    for (size_t i = 0; i < image.radiance.size(); ++i) {
        CHECK(image.radiance[i] == image.direct[i] + image.indirect[i]);
        CHECK(image.indirect[i] >= 0.0f);
        if (image.direct[i] == 0.0f && image.indirect[i] > 0.0f) ++indirect_only;
    }
    return indirect_only;
}

}  // namespace

namespace {

// The in-repo Cornell box's direct light against the CPU path; `lambert`: every material made a
// pure Lambertian (scene::use_lambertian_materials), whose BRDF is base colour / pi.
void check_direct_against_cpu_path(bool lambert) {
    vplkit::Context& ctx = vplkit::test::context();
    auto scene = vplkit::scene::load_gltf(kCornellPoint);
    const auto original_materials = scene.materials;
    if (lambert) vplkit::scene::use_lambertian_materials(scene);
    REQUIRE(scene.lights.size() == 1);
    const uint32_t width = 48, height = 40;
    vplkit::Renderer renderer(ctx, scene);
    const auto& camera = scene.camera();
    vplkit::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    const auto image = renderer.render(camera, settings);
    CHECK(image.non_finite_pixels == 0);

    const auto triangles = reference_triangles(scene);
    const glm::dmat4 clip_to_world =
        glm::inverse(glm::dmat4(vplkit::camera_view(camera, width, height).view_projection));
    const auto& light = scene.lights[0];
    vplkit::reference::LightDesc light_desc;
    light_desc.kind = vplkit::reference::LightKind::point;
    light_desc.position = {light.position.x, light.position.y, light.position.z};
    light_desc.intensity = {double(light.color.x) * light.intensity, double(light.color.y) * light.intensity,
                            double(light.color.z) * light.intensity};

    int compared = 0, skipped = 0, lit = 0;
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            // The pixel centre's ray: unproject Vulkan clip points at depth 0 and 1.
            const double nx = (x + 0.5) / width * 2.0 - 1.0, ny = (y + 0.5) / height * 2.0 - 1.0;
            glm::dvec4 near = clip_to_world * glm::dvec4(nx, ny, 0.0, 1.0);
            glm::dvec4 far = clip_to_world * glm::dvec4(nx, ny, 1.0, 1.0);
            const glm::dvec3 a = glm::dvec3(near) / near.w, b = glm::dvec3(far) / far.w;
            vplkit::reference::Ray ray;
            ray.origin = {a.x, a.y, a.z};
            ray.direction = {b.x - a.x, b.y - a.y, b.z - a.z};
            ray.tmin = 0.0;
            ray.tmax = 1.0;
            const auto hit = vplkit::reference::closest_hit(triangles, ray);
            if (edge_margin(triangles, ray) < 1e-3) {
                ++skipped;
                continue;
            }
            if (!hit.hit) {  // past the open box: the background, black by default
                ++compared;
                for (int c = 0; c < 3; ++c) CHECK(image.radiance[(y * width + x) * 3 + c] == 0.0f);
                continue;
            }
            const Vec3 p = {ray.origin[0] + hit.t * ray.direction[0], ray.origin[1] + hit.t * ray.direction[1],
                            ray.origin[2] + hit.t * ray.direction[2]};
            // Face normal turned to the viewer; the Cornell box has flat normals.
            const auto& tri = triangles[hit.triangle];
            const Vec3 e1 = {tri.v1[0] - tri.v0[0], tri.v1[1] - tri.v0[1], tri.v1[2] - tri.v0[2]};
            const Vec3 e2 = {tri.v2[0] - tri.v0[0], tri.v2[1] - tri.v0[1], tri.v2[2] - tri.v0[2]};
            Vec3 n = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            const double n_length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            double facing = 0.0;
            for (int c = 0; c < 3; ++c) facing += n[c] * ray.direction[c];
            for (double& c : n) c = (facing > 0.0 ? -c : c) / n_length;
            Vec3 wo = {camera.position.x - p[0], camera.position.y - p[1], camera.position.z - p[2]};
            const double wo_length = std::sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
            for (double& c : wo) c /= wo_length;
            const auto& material = original_materials[scene.triangle_materials[hit.triangle]];

            Vec3 expected = {material.emission().x, material.emission().y, material.emission().z};
            const auto s = vplkit::reference::sample_light(light_desc, p);
            const double cos_theta = n[0] * s.wi[0] + n[1] * s.wi[1] + n[2] * s.wi[2];
            vplkit::reference::Ray shadow;
            shadow.origin = p;
            shadow.direction = s.wi;
            shadow.tmin = 1e-4;
            shadow.tmax = s.distance;
            if (edge_margin(triangles, shadow) < 1e-3) {
                ++skipped;
                continue;
            }
            if (cos_theta > 0.0 && !vplkit::reference::occluded(triangles, shadow)) {
                ++lit;
                const Vec3 base = {material.base_color_factor.x, material.base_color_factor.y,
                                   material.base_color_factor.z};
                const double pi = std::numbers::pi;
                const Vec3 f = lambert ? Vec3{base[0] / pi, base[1] / pi, base[2] / pi}
                                       : vplkit::reference::gltf_brdf(n, wo, s.wi, base, material.roughness_factor,
                                                                      material.metallic_factor);
                for (int c = 0; c < 3; ++c) expected[c] += f[c] * s.irradiance[c] * cos_theta;
            }
            ++compared;
            CAPTURE(x);
            CAPTURE(y);
            for (int c = 0; c < 3; ++c) {
                CHECK(double(image.radiance[(y * width + x) * 3 + c]) ==
                      doctest::Approx(expected[c]).epsilon(2e-3).scale(1e-6 / 2e-3));
            }
        }
    }
    CHECK(skipped * 5 < compared);
    CHECK(lit * 2 > compared);  // most of the box sees the light
    CHECK(lit < compared);      // and the blocks cast shadows
}

}  // namespace

TEST_CASE("direct render: the in-repo Cornell box matches a brute-force CPU path at pixel centres") {
    check_direct_against_cpu_path(false);
}

TEST_CASE("direct render: with every material made Lambertian (--brdf lambert) the BRDF is base colour / pi") {
    check_direct_against_cpu_path(true);
}

TEST_CASE("direct render: a scene without any light is refused by name") {
    vplkit::Context& ctx = vplkit::test::context();
    auto scene = vplkit::scene::load_gltf(kCornellPoint);
    scene.lights.clear();
    CHECK_THROWS_WITH_AS(vplkit::Renderer(ctx, scene), doctest::Contains("the scene has no light"), vplkit::Error);
}

TEST_CASE("direct render: an emissive quad without an emissive texture shows its emission and lights the room") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(VPLKIT_SOURCE_DIR "/scenes/cornell_emissive/cornell_emissive.gltf");
    REQUIRE(scene.lights.empty());
    REQUIRE_FALSE(scene.emissive_triangles.empty());
    const auto& material = scene.materials[scene.triangle_materials[scene.emissive_triangles[0]]];
    REQUIRE(material.emissive_texture == vplkit::scene::kNoTexture);
    vplkit::Renderer renderer(ctx, scene);
    vplkit::RenderSettings settings;
    settings.width = 64;
    settings.height = 64;
    settings.direct_samples = 4;
    const auto image = renderer.render(scene.camera(), settings);
    CHECK(image.non_finite_pixels == 0);
    // Some pixel sees the quad itself: its radiance is the material's emission (factor x strength;
    // the G-buffer stores it in half floats), plus nothing else (no light reaches its front).
    int emitter_pixels = 0, lit_pixels = 0;
    for (size_t i = 0; i < image.radiance.size(); i += 3) {
        const float r = image.radiance[i];
        if (std::abs(r - material.emission().x) <= 1e-3f * material.emission().x)
            ++emitter_pixels;
        else if (r > 0.0f)
            ++lit_pixels;
    }
    CHECK(emitter_pixels > 0);
    CHECK(lit_pixels > 64 * 64 / 2);  // the walls, floor and blocks get the quad's light
}

TEST_CASE("render with exact indirect light: the parts add up and the seed fixes the image") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = small_exact_settings();
    settings.vpl_paths = 64;
    settings.vpl_bounces = 2;
    settings.seed = 3;
    uint32_t progress_calls = 0;
    settings.progress = [&](uint32_t done, uint32_t total) {
        ++progress_calls;
        CHECK(done <= total);
    };
    const auto a = renderer.render(scene.camera(), settings);
    CHECK(a.non_finite_pixels == 0);
    CHECK(a.dropped_pixels == 0);
    CHECK(a.vpl_count > 0);
    CHECK(progress_calls > 0);
    CHECK(check_parts_add_up(a) > 0);  // the blocks' shadows get light from the walls
    // Same seed, same VPL set and so the same image, up to float rounding: the tracer appends
    // VPLs with an atomic counter, so their order (and the gather's summation order) may change.
    const auto b = renderer.render(scene.camera(), settings);
    for (size_t i = 0; i < a.radiance.size(); ++i) {
        CHECK(b.radiance[i] == doctest::Approx(a.radiance[i]).epsilon(1e-5).scale(1e-9));
    }
    settings.seed = 4;
    const auto c = renderer.render(scene.camera(), settings);
    CHECK(c.indirect != a.indirect);
    CHECK(c.direct == a.direct);
}

TEST_CASE("render with BRSM indirect light: one bounce, finite, the same seed gives the same image") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = small_exact_settings();
    settings.vpl_source = vplkit::VplSource::brsm;
    settings.brsm.vpl_count = 64;
    settings.rsm_resolution = 16;
    settings.seed = 3;
    const auto a = renderer.render(scene.camera(), settings);
    CHECK(a.non_finite_pixels == 0);
    CHECK(a.dropped_pixels == 0);
    CHECK(a.vpl_count == 64);
    CHECK(a.notes.empty());
    CHECK(check_parts_add_up(a) > 0);
    // BRSM writes its VPLs in a fixed order: the same seed gives the same image exactly.
    const auto b = renderer.render(scene.camera(), settings);
    CHECK(b.radiance == a.radiance);
    settings.seed = 4;
    CHECK(renderer.render(scene.camera(), settings).indirect != a.indirect);

    // A spot light aimed out of the box's open front, from in front of it, reaches no surface:
    // it gets its share of VPLs, places none, and the frame says so.
    auto with_spot = scene;
    vplkit::scene::Light spot;
    spot.type = vplkit::scene::LightType::spot;
    spot.name = "away";
    spot.position = {0.0f, 1.0f, 3.0f};
    spot.direction = {0.0f, 0.0f, 1.0f};
    spot.outer_cone_angle = 0.3f;
    with_spot.lights.push_back(spot);
    vplkit::Renderer spot_renderer(ctx, with_spot);
    const auto s = spot_renderer.render(with_spot.camera(), settings);
    REQUIRE(s.notes.size() == 1);
    CHECK(s.notes[0].find("'away': its shadow map holds no surface") != std::string::npos);
    CHECK(s.vpl_count < 64);
    CHECK(s.vpl_count > 0);

    // --vpls-only: the VPLs and the G-buffer's positions, no indirect light.
    settings.vpls_only = true;
    const auto v = renderer.render(scene.camera(), settings);
    CHECK(v.vpls.size() == 64);
    CHECK(v.gbuffer_position.size() == size_t(4) * settings.width * settings.height);
    for (float x : v.indirect) CHECK(x == 0.0f);
}

TEST_CASE("render with BRSM: a scene lit only by emissive triangles is refused by name") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(VPLKIT_SOURCE_DIR "/scenes/cornell_emissive/cornell_emissive.gltf");
    vplkit::Renderer renderer(ctx, scene);
    auto settings = small_exact_settings(16, 16);
    settings.vpl_source = vplkit::VplSource::brsm;
    CHECK_THROWS_WITH_AS(renderer.render(scene.camera(), settings), doctest::Contains("use `vpl_source` ir"),
                         vplkit::Error);
}

TEST_CASE("render: BRSM and one-bounce instant radiosity estimate the same indirect light") {
    // Both VPL sets estimate, without bias, the light the surfaces reflect once (BRSM with its
    // defensive term covers every lit texel): over seeds, the image's total indirect radiance must
    // agree. Tolerance: 4 sigma of the difference of the two means, plus 3% for what differs by
    // construction: BRSM places a VPL at a texel's centre for the whole texel's flux (64^2 faces),
    // and the 1/d^2 clamp near creases weighs that placement. A second, bluer point light makes
    // BRSM share its VPLs and place them light by light.
    vplkit::Context& ctx = vplkit::test::context();
    auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::scene::Light blue;
    blue.name = "blue";
    blue.position = {0.5f, 1.0f, 0.4f};  // above the short block
    blue.color = {0.5f, 0.7f, 1.0f};
    blue.intensity = 3.0f;
    scene.lights.push_back(blue);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = small_exact_settings();
    settings.rsm_resolution = 64;
    settings.brsm.vpl_count = 600;
    settings.vpl_paths = 600;
    settings.vpl_bounces = 1;
    auto image_total = [](const vplkit::RenderedImage& image) {
        double sum = 0;
        for (float v : image.indirect) sum += v;
        return sum;
    };
    const int seeds = 8;
    std::vector<double> totals[2];
    for (int source = 0; source < 2; ++source) {
        settings.vpl_source = source == 0 ? vplkit::VplSource::ir : vplkit::VplSource::brsm;
        for (int seed = 0; seed < seeds; ++seed) {
            settings.seed = uint32_t(seed);
            totals[source].push_back(image_total(renderer.render(scene.camera(), settings)));
        }
    }
    double mean[2], variance_of_mean[2];
    for (int s = 0; s < 2; ++s) {
        mean[s] = 0;
        for (double t : totals[s]) mean[s] += t / seeds;
        double var = 0;
        for (double t : totals[s]) var += (t - mean[s]) * (t - mean[s]) / (seeds - 1);
        variance_of_mean[s] = var / seeds;
    }
    const double bound = 4.0 * std::sqrt(variance_of_mean[0] + variance_of_mean[1]) + 0.03 * mean[0];
    MESSAGE("indirect total: ir " << mean[0] << " +- " << std::sqrt(variance_of_mean[0]) << ", brsm " << mean[1]
                                  << " +- " << std::sqrt(variance_of_mean[1]));
    CHECK(mean[0] > 0);
    CHECK(std::abs(mean[1] - mean[0]) <= bound);
}

// ---------------------------------------------------------------------------------------------
// Sampled indirect light: sst, rtslc and hybrid in a whole frame, on a 64 x 48 Cornell box with
// the VPLs of 256 light paths x 2 bounces.

namespace {

constexpr uint32_t kSampledWidth = 64, kSampledHeight = 48;

vplkit::RenderSettings sampled_settings(vplkit::GiMethod method, uint32_t width = kSampledWidth,
                                        uint32_t height = kSampledHeight) {
    vplkit::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.method = method;
    settings.vpl_paths = 256;
    settings.vpl_bounces = 2;
    settings.samples_per_pixel = 8;
    settings.block_size = 8;
    settings.direct_samples = 1;  // the scene has none
    return settings;
}

// Pixels the G-buffer covers (a surface drawn there), from a --vpls-only frame of the same size.
uint32_t covered_pixels(vplkit::Renderer& renderer, const vplkit::scene::Camera& camera,
                        vplkit::RenderSettings settings) {
    settings.vpls_only = true;
    const auto image = renderer.render(camera, settings);
    uint32_t covered = 0;
    for (size_t i = 3; i < image.gbuffer_position.size(); i += 4) covered += image.gbuffer_position[i] > 0.5f ? 1 : 0;
    return covered;
}

double indirect_total(const vplkit::RenderedImage& image) {
    double sum = 0.0;
    for (float v : image.indirect) sum += v;
    return sum;
}

bool all_finite(const std::vector<float>& values) {
    for (float v : values) {
        if (!std::isfinite(v)) return false;
    }
    return true;
}

bool has_timing(const vplkit::RenderedImage& image, const std::string& name) {
    for (const auto& t : image.timings) {
        if (t.name == name) return true;
    }
    return false;
}

constexpr vplkit::GiMethod kSampledMethods[] = {vplkit::GiMethod::sst, vplkit::GiMethod::rtslc,
                                                vplkit::GiMethod::hybrid};

}  // namespace

TEST_CASE("render with sst, rtslc and hybrid: finite, counted, timed, and the seed fixes the image") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    const uint32_t covered = covered_pixels(renderer, scene.camera(), sampled_settings(vplkit::GiMethod::exact));
    REQUIRE(covered > kSampledWidth * kSampledHeight / 2);  // the box fills most of the frame
    REQUIRE(covered < kSampledWidth * kSampledHeight);      // and its open front shows the background
    for (const vplkit::GiMethod method : kSampledMethods) {
        const std::string name = vplkit::gi_method_name(method);
        CAPTURE(name);
        auto settings = sampled_settings(method);
        settings.seed = 3;
        const auto a = renderer.render(scene.camera(), settings);
        CHECK(a.non_finite_pixels == 0);
        CHECK(all_finite(a.indirect));
        CHECK(a.vpl_count > 0);
        CHECK(a.notes.empty());
        CHECK(a.gi_width == kSampledWidth);
        CHECK(a.gi_height == kSampledHeight);
        CHECK(check_parts_add_up(a) > 0);  // the blocks' shadows get light from the walls
        CHECK(*std::max_element(a.indirect.begin(), a.indirect.end()) > 0.0f);
        const vplkit::stages::GiCounts& c = a.gi_counts;
        CHECK(c.dropped_samples == 0);
        CHECK(c.dropped_pixels == 0);
        CHECK(a.dropped_pixels == 0);
        CHECK(c.cut_short == 0);
        // sst: spp traversals from the root per covered pixel; rtslc: one per node of a full cut
        // (the tree has far more than 8 leaves, so every cut has 8 nodes); hybrid: one per node
        // of the pixel's blended cut, which may hold fewer than spp.
        const uint64_t budget = uint64_t(covered) * settings.samples_per_pixel;
        if (method == vplkit::GiMethod::hybrid) {
            CHECK(c.traversals <= budget);
            CHECK(c.traversals > 0);
            CHECK(c.mock_cut_pixels <= covered);
        } else {
            CHECK(c.traversals == budget);
            CHECK(c.mock_cut_pixels == 0);
        }
        CHECK(c.levels > 0);
        CHECK(c.levels_per_traversal() > 0.0);
        MESSAGE(name << ": " << c.traversals << " traversals (covered x spp = " << budget << "), "
                     << c.levels_per_traversal() << " levels per traversal, " << c.dead_branches << " dead branches, "
                     << c.mock_cut_pixels << " mock-cut pixels of " << covered);
        // The sort, the one tree the method reads (the planner leaves the other out) and the
        // method's own passes are timed.
        const bool reads_sst = method != vplkit::GiMethod::rtslc;
        CHECK(has_timing(a, "sort"));
        CHECK(has_timing(a, "build sst") == reads_sst);
        CHECK(has_timing(a, "light tree levels") == !reads_sst);
        if (method == vplkit::GiMethod::sst) CHECK(has_timing(a, "sst gi"));
        if (method == vplkit::GiMethod::rtslc) {
            CHECK(has_timing(a, "rtslc cuts"));
            CHECK(has_timing(a, "rtslc gi"));
        }
        if (method == vplkit::GiMethod::hybrid) {
            CHECK(has_timing(a, "hybrid cuts"));
            CHECK(has_timing(a, "hybrid gi"));
        }
        // The same seed: the same image, bit for bit; another seed: another one.
        const auto b = renderer.render(scene.camera(), settings);
        CHECK(b.indirect == a.indirect);
        CHECK(b.radiance == a.radiance);
        CHECK(b.gi_counts.traversals == a.gi_counts.traversals);
        CHECK(b.gi_counts.levels == a.gi_counts.levels);
        settings.seed = 4;
        const auto other = renderer.render(scene.camera(), settings);
        CHECK(other.indirect != a.indirect);
        CHECK(other.direct == a.direct);
    }
}

TEST_CASE("render: sst, rtslc and hybrid agree with exact on the image's total indirect light") {
    // Per seed, every method renders that seed's VPL set (the tracer's: the same for all four)
    // and its image total is divided by exact's; the ratios are averaged over 8 seeds. rtslc is
    // unbiased for a given VPL set, so only its noise remains; sst and hybrid are biased by
    // design (a substitute position stands for a cluster; hybrid's blended cuts need not
    // partition the tree and its traversals stop early), so theirs bounds that bias here.
    // Measured on lavapipe (64 x 48, 348 VPLs at seed 3, 8 spp, 8 x 8 blocks), mean ratio
    // (sd of one seed's): sst 0.9972 (0.024), rtslc 1.0015 (0.015), hybrid 1.0026 (0.017); one
    // seed's ratio ranged over 0.963..1.030 (sst), 0.976..1.028 (rtslc), 0.980..1.022 (hybrid).
    // Tolerance: rtslc 3% (4 standard errors of the 8-seed mean are 2.2%), sst and hybrid 5%
    // (their bias in this scene is well under 1%: the margin is for noise and other drivers),
    // one seed 10%.
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    const int seeds = 8;
    const double tolerance[3] = {0.05, 0.03, 0.05};  // sst, rtslc, hybrid
    double ratio_sum[3] = {0, 0, 0}, ratio_sq[3] = {0, 0, 0};
    for (int seed = 0; seed < seeds; ++seed) {
        auto settings = sampled_settings(vplkit::GiMethod::exact);
        settings.seed = uint32_t(seed);
        const double exact = indirect_total(renderer.render(scene.camera(), settings));
        REQUIRE(exact > 0.0);
        for (int m = 0; m < 3; ++m) {
            settings.method = kSampledMethods[m];
            const double ratio = indirect_total(renderer.render(scene.camera(), settings)) / exact;
            CAPTURE(seed);
            CAPTURE(std::string(vplkit::gi_method_name(settings.method)));
            CHECK(ratio == doctest::Approx(1.0).epsilon(0.10));
            ratio_sum[m] += ratio;
            ratio_sq[m] += ratio * ratio;
        }
    }
    for (int m = 0; m < 3; ++m) {
        const std::string name = vplkit::gi_method_name(kSampledMethods[m]);
        const double mean = ratio_sum[m] / seeds;
        const double sd = std::sqrt(std::max(0.0, (ratio_sq[m] - seeds * mean * mean) / (seeds - 1)));
        MESSAGE(name << ": mean ratio to exact " << mean << " over " << seeds << " seeds, sd " << sd);
        CAPTURE(name);
        CHECK(mean == doctest::Approx(1.0).epsilon(tolerance[m]));
    }
}

TEST_CASE("render at half GI resolution: half-size indirect light, upsampled, close to full resolution") {
    // The same VPLs (seed) at full and at half GI resolution; the half image's total over the
    // full one's. Measured on lavapipe (64 x 48, GI at 32 x 24): exact 0.972..0.982 over 9 seeds
    // (always ~2% low: at this size most covered pixels (1715 of 2304) find no similar half
    // sample within the upsampler's distance and take the nearest one, 13 get none); the sampled
    // methods, noisier at a quarter of the samples, one seed 0.90..1.12, the mean of seeds
    // 10..13 sst 0.956, rtslc 0.985, hybrid 0.990 (of 10..17: 0.987, 0.965, 0.985).
    // Tolerance: exact 5%, the sampled methods' 4-seed mean 10%.
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    const uint32_t covered = covered_pixels(renderer, scene.camera(), sampled_settings(vplkit::GiMethod::exact));
    for (const vplkit::GiMethod method :
         {vplkit::GiMethod::exact, vplkit::GiMethod::sst, vplkit::GiMethod::rtslc, vplkit::GiMethod::hybrid}) {
        const std::string name = vplkit::gi_method_name(method);
        CAPTURE(name);
        const bool exact = method == vplkit::GiMethod::exact;
        const uint32_t seeds = exact ? 1 : 4;
        double ratio_sum = 0.0;
        for (uint32_t seed = 10; seed < 10 + seeds; ++seed) {
            CAPTURE(seed);
            auto settings = sampled_settings(method);
            settings.seed = seed;
            const auto full = renderer.render(scene.camera(), settings);
            settings.half_resolution_gi = true;
            const auto half = renderer.render(scene.camera(), settings);
            CHECK(half.gi_width == vplkit::stages::half_resolution(kSampledWidth));
            CHECK(half.gi_height == vplkit::stages::half_resolution(kSampledHeight));
            CHECK(half.gi_width == kSampledWidth / 2);
            CHECK(half.gi_height == kSampledHeight / 2);
            CHECK(half.width == kSampledWidth);
            CHECK(half.height == kSampledHeight);
            CHECK(half.indirect.size() == full.indirect.size());
            CHECK(half.non_finite_pixels == 0);
            CHECK(all_finite(half.indirect));
            CHECK(half.notes.empty());
            CHECK(half.direct == full.direct);
            CHECK(check_parts_add_up(half) > 0);
            CHECK(has_timing(half, "gbuffer downsample"));
            CHECK(has_timing(half, "upsample"));
            CHECK_FALSE(has_timing(full, "upsample"));
            CHECK(half.upsample_counts.fallback_pixels + half.upsample_counts.empty_pixels <= covered);
            if (!exact) {
                const auto& c = half.gi_counts;
                CHECK(c.dropped_samples == 0);
                CHECK(c.cut_short == 0);
                CHECK(c.traversals > 0);
                CHECK(c.levels_per_traversal() > 0.0);
                // Only the half G-buffer's pixels are shaded: a quarter of the full frame's.
                CHECK(c.traversals <= uint64_t(half.gi_width) * half.gi_height * settings.samples_per_pixel);
                CHECK(c.traversals < full.gi_counts.traversals / 2);
                if (method == vplkit::GiMethod::hybrid) CHECK(c.mock_cut_pixels <= half.gi_width * half.gi_height);
            }
            const double ratio = indirect_total(half) / indirect_total(full);
            ratio_sum += ratio;
            if (exact) {
                MESSAGE("exact: half / full total " << ratio << "; " << half.upsample_counts.fallback_pixels << " of "
                                                    << covered << " covered pixels took the nearest sample, "
                                                    << half.upsample_counts.empty_pixels << " none");
            }
        }
        const double mean = ratio_sum / seeds;
        MESSAGE(name << ": half / full total " << mean << " (mean of " << seeds << " seeds)");
        CHECK(mean == doctest::Approx(1.0).epsilon(exact ? 0.05 : 0.10));
    }
}

TEST_CASE("render with hybrid from BRSM VPLs: finite, counted, the seed fixes the image") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = sampled_settings(vplkit::GiMethod::hybrid);
    settings.vpl_source = vplkit::VplSource::brsm;
    settings.brsm.vpl_count = 256;
    settings.rsm_resolution = 32;
    settings.seed = 3;
    const uint32_t covered = covered_pixels(renderer, scene.camera(), settings);
    const auto a = renderer.render(scene.camera(), settings);
    CHECK(a.vpl_count == 256);
    CHECK(a.notes.empty());
    CHECK(a.non_finite_pixels == 0);
    CHECK(all_finite(a.indirect));
    CHECK(check_parts_add_up(a) > 0);
    CHECK(a.gi_counts.dropped_samples == 0);
    CHECK(a.gi_counts.cut_short == 0);
    CHECK(a.gi_counts.traversals > 0);
    CHECK(a.gi_counts.traversals <= uint64_t(covered) * settings.samples_per_pixel);
    CHECK(a.gi_counts.levels_per_traversal() > 0.0);
    CHECK(a.gi_counts.mock_cut_pixels <= covered);
    CHECK(has_timing(a, "hybrid gi"));
    // BRSM writes its VPLs in a fixed order: the same seed gives the same image exactly.
    const auto b = renderer.render(scene.camera(), settings);
    CHECK(b.radiance == a.radiance);
    settings.seed = 4;
    CHECK(renderer.render(scene.camera(), settings).indirect != a.indirect);
    // And it agrees with exact on the same (seed's) BRSM VPLs. Measured on lavapipe, hybrid /
    // exact image total for seeds 0..7: 0.983, 0.988, 0.999, 0.979, 0.988, 0.999, 0.984, 0.998
    // (~1% low on average). Tolerance: the mean of seeds 0..3 within
    // 5%, each within 10%.
    double ratio_sum = 0.0;
    for (uint32_t seed = 0; seed < 4; ++seed) {
        CAPTURE(seed);
        settings.seed = seed;
        settings.method = vplkit::GiMethod::exact;
        const double exact = indirect_total(renderer.render(scene.camera(), settings));
        REQUIRE(exact > 0.0);
        settings.method = vplkit::GiMethod::hybrid;
        const double ratio = indirect_total(renderer.render(scene.camera(), settings)) / exact;
        CHECK(ratio == doctest::Approx(1.0).epsilon(0.10));
        ratio_sum += ratio;
    }
    MESSAGE("BRSM VPLs: hybrid / exact total " << ratio_sum / 4 << " (mean of 4 seeds)");
    CHECK(ratio_sum / 4 == doctest::Approx(1.0).epsilon(0.05));
}

TEST_CASE("render with sampled indirect light when no VPL is placed: a note and no indirect light") {
    // The scene's only light is a spot aimed out of the box's open front from in front of it:
    // its light paths meet nothing, so no VPL is placed.
    vplkit::Context& ctx = vplkit::test::context();
    auto scene = vplkit::scene::load_gltf(kCornellPoint);
    scene.lights.clear();
    vplkit::scene::Light spot;
    spot.type = vplkit::scene::LightType::spot;
    spot.name = "away";
    spot.position = {0.0f, 1.0f, 3.0f};
    spot.direction = {0.0f, 0.0f, 1.0f};
    spot.outer_cone_angle = 0.3f;
    scene.lights.push_back(spot);
    vplkit::Renderer renderer(ctx, scene);
    for (const vplkit::GiMethod method : kSampledMethods) {
        for (const bool half : {false, true}) {
            const std::string name = vplkit::gi_method_name(method);
            CAPTURE(name);
            CAPTURE(half);
            auto settings = sampled_settings(method);
            settings.half_resolution_gi = half;
            const auto image = renderer.render(scene.camera(), settings);
            CHECK(image.vpl_count == 0);
            REQUIRE(image.notes.size() == 1);
            CHECK(image.notes[0].find("no VPLs were placed") != std::string::npos);
            CHECK(image.non_finite_pixels == 0);
            // The samplers ran over trees of padding alone (the frame reads no count back
            // before they run): every traversal found no light, none was dropped.
            CHECK(image.gi_counts.dropped_samples == 0);
            CHECK(std::count_if(image.indirect.begin(), image.indirect.end(), [](float v) { return v != 0.0f; }) == 0);
        }
    }
    // BRSM VPLs: the spot's shadow map sees nothing, so the light has none, and the frame none.
    auto settings = sampled_settings(vplkit::GiMethod::hybrid);
    settings.vpl_source = vplkit::VplSource::brsm;
    settings.brsm.vpl_count = 64;
    settings.rsm_resolution = 16;
    const auto image = renderer.render(scene.camera(), settings);
    CHECK(image.vpl_count == 0);
    REQUIRE(image.notes.size() == 2);
    CHECK(image.notes[0].find("'away': its shadow map holds no surface") != std::string::npos);
    CHECK(image.notes[1].find("no VPLs were placed") != std::string::npos);
    CHECK(image.non_finite_pixels == 0);
    CHECK(std::count_if(image.indirect.begin(), image.indirect.end(), [](float v) { return v != 0.0f; }) == 0);
    // A bad sampling option is refused although no VPL would ever reach the stage that checks it.
    auto bad = sampled_settings(vplkit::GiMethod::rtslc);
    bad.interleave = 3;
    CHECK_THROWS_WITH_AS(renderer.render(scene.camera(), bad), doctest::Contains("interleave 3"), vplkit::Error);
}

TEST_CASE("render: the frame counter gives sst, rtslc and hybrid other random numbers each frame, the same VPLs") {
    // Temporal accumulation averages frames: frames that drew the same numbers would average to
    // one frame's noise. The same seed and frame repeat the image bit for bit.
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    for (const vplkit::GiMethod method : kSampledMethods) {
        const std::string name = vplkit::gi_method_name(method);
        CAPTURE(name);
        auto settings = sampled_settings(method);
        settings.seed = 5;
        const auto frame0 = renderer.render(scene.camera(), settings);
        settings.frame = 1;
        const auto frame1 = renderer.render(scene.camera(), settings);
        CHECK(frame1.reused_vpls);  // the VPLs follow the seed, not the frame
        CHECK(frame1.indirect != frame0.indirect);
        size_t differing = 0, lit = 0;
        for (size_t i = 0; i < frame0.indirect.size(); ++i) {
            lit += frame0.indirect[i] > 0.0f;
            differing += frame0.indirect[i] != frame1.indirect[i];
        }
        CHECK(differing > lit / 2);  // most lit pixels, not a few
        const auto again = renderer.render(scene.camera(), settings);
        CHECK(again.indirect == frame1.indirect);
    }
}

TEST_CASE("render: sigma_max is a fraction of the scene's size unless given absolutely") {
    // The thesis' absolute 0.3 was chosen for its ~25 m Sponza; in a 2 m room it merges clusters
    // as thick as 15% of the room, whose substitutes lost light (README, Energy).
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = sampled_settings(vplkit::GiMethod::hybrid);
    const auto relative = renderer.render(scene.camera(), settings);
    const float expected = vplkit::kSigmaMaxSceneFraction * renderer.bvh().scene_scale;
    CHECK(relative.sst_sigma_max == expected);
    settings.sigma_max_scene_fraction.reset();
    settings.sst.sigma_max = expected;
    const auto absolute = renderer.render(scene.camera(), settings);
    CHECK(absolute.sst_sigma_max == expected);
    CHECK(absolute.indirect == relative.indirect);
    settings.sst.sigma_max = 0.3f;
    CHECK(renderer.render(scene.camera(), settings).sst_sigma_max == 0.3f);
    settings.sigma_max_scene_fraction = -1.0f;
    CHECK_THROWS_AS(renderer.render(scene.camera(), settings), vplkit::Error);
}
