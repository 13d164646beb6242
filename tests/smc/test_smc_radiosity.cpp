// smc_radiosity.comp (Alg. 1 lines 7 and 18, the SMC paper sec. 3.2.3): B(y) = rho(y) E(y) by paths
// with next-event estimation, from each record's own seed.
// - One bounce, a point light over a floor with an occluding square: the estimate has no
//   variance (one emitter, pmf 1), so it must equal rho I cos / d^2 (smc_point_light_radiosity)
//   within 1e-5 relative (float rounding of a few products), and exactly 0 in the occluder's
//   shadow, for a black triangle and for a record without a triangle. Fails on a wrong cosine,
//   falloff, albedo, pmf or shadow ray.
// - moved VPLs (line 18): only the slots the moves name are estimated, and their choosing
//   estimate (choice_radiosity) is kept; fails if another slot is touched.
// - every VPL (line 18 after the light moved): each of the first |Y| gets the closed form for the
//   light where it is now, in both estimates; a dead VPL (its surface moved away) gets zero in
//   both; slots past |Y| stay. Fails if a survivor keeps the old light's radiosity.
// - Two bounces, floor and ceiling with the light between: the mean over n records (each its
//   own seed) against rho_f (E_direct + rho_c integral of E_c cos cos / (pi d^2) over the
//   ceiling) by a 400 x 400 midpoint quadrature in double (error ~1e-5 relative), within 4
//   sigma / sqrt(n) (sigma: the records' sample deviation) plus 1e-3 relative for the
//   quadrature, for two record counts (64 and 512). Fails if the second vertex's light is lost,
//   doubled, or not weighted by the ceiling's rho (the bounce is ~15% of the total; 4 sigma of
//   the mean is ~1% at n = 512).
// - One bounce from a point light and an emissive triangle together, chosen by their CDF (0.4,
//   0.6): the mean over 64 and 512 records against the point light's closed form plus the
//   triangle's L cos cos / d^2 integrated by a 300^2-cell quadrature, within 4 sigma / sqrt(n) +
//   1e-3 relative. Fails on a wrong pmf, area, emitter side or cosine.
// No path may be cut short by lavapipe's loop limit (counters.cut_short = 0).

#include "smc_reference.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/smc_radiosity.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

namespace {

using vplkit::reference::Triangle;
using vplkit::shaders::SmcCounters;
using vplkit::shaders::SmcVpl;

vplkit::Buffer make(size_t bytes, const char* name) {
    return vplkit::Buffer::create(vplkit::test::context(), std::max<size_t>(bytes, 16),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
}

// A square [lo, hi]^2 at height z as two triangles, facing +z (up) or -z.
void add_square(std::vector<glm::vec3>& triangles, float lo, float hi, float z, bool up) {
    const glm::vec3 a{lo, lo, z}, b{hi, lo, z}, c{hi, hi, z}, d{lo, hi, z};
    const std::array<glm::vec3, 6> quad =
        up ? std::array<glm::vec3, 6>{a, b, c, a, c, d} : std::array<glm::vec3, 6>{a, c, b, a, d, c};
    triangles.insert(triangles.end(), quad.begin(), quad.end());
}

std::vector<Triangle> reference_triangles(const std::vector<glm::vec3>& t) {
    std::vector<Triangle> out;
    for (size_t i = 0; i + 2 < t.size(); i += 3) {
        out.push_back(
            {{t[i].x, t[i].y, t[i].z}, {t[i + 1].x, t[i + 1].y, t[i + 1].z}, {t[i + 2].x, t[i + 2].y, t[i + 2].z}});
    }
    return out;
}

struct Setup {
    std::vector<glm::vec3> triangles;  // the BVH's, ids = their order
    std::vector<glm::vec4> albedo;     // per triangle
    glm::vec3 light{0.0f};
    glm::vec3 intensity{0.0f};  // colour x candela
    // An emissive triangle besides the point light, chosen with probability 1 - light_share.
    std::optional<vplkit::shaders::EmitterTriangle> emitter;
    float light_share = 1.0f;
};

SmcVpl record(glm::vec3 p, glm::vec3 n, uint32_t triangle, uint32_t seed) {
    SmcVpl v{};
    v.position = {p.x, p.y, p.z};
    v.normal = {n.x, n.y, n.z};
    v.triangle = triangle;
    v.seed = seed;
    v.radiosity = {-1.0f, -1.0f, -1.0f};  // what an unestimated slot keeps
    v.choice_radiosity = {-2.0f, -2.0f, -2.0f};
    return v;
}

struct Estimated {
    std::vector<SmcVpl> records;
    uint32_t cut_short = 0;
};

// Runs smc_radiosity over `records`: the first `count` as candidates (moves empty), or the slots
// `moves` name, or with every_vpl the first `count` as the VPLs of Y.
Estimated run(const Setup& s, const std::vector<SmcVpl>& records, uint32_t count, uint32_t samples, uint32_t bounces,
              const std::vector<std::array<uint32_t, 2>>& moves = {}, bool every_vpl = false) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t budget = uint32_t(records.size());
    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(s.triangles));
    vplkit::scene::Light light;
    light.type = vplkit::scene::LightType::point;
    light.position = s.light;
    light.color = s.intensity / 10.0f;
    light.intensity = 10.0f;
    const std::vector<vplkit::scene::Light> lights = {light};
    const auto gpu_lights = vplkit::upload_lights(ctx, lights);
    auto emissive = make(sizeof(vplkit::shaders::EmitterTriangle), "emissive");
    emissive.upload(
        std::vector<vplkit::shaders::EmitterTriangle>{s.emitter.value_or(vplkit::shaders::EmitterTriangle{})});
    auto cdf = make(16, "emitter cdf");
    cdf.upload(std::vector<float>{s.emitter ? s.light_share : 1.0f, 1.0f, 1.0f, 1.0f});
    auto albedo = make(s.albedo.size() * sizeof(glm::vec4), "albedo");
    albedo.upload(s.albedo);
    auto record_buffer = make(budget * sizeof(SmcVpl), "records");
    record_buffer.upload(records);
    auto move_buffer = make(budget * 8, "moves");
    std::vector<std::array<uint32_t, 2>> padded = moves;
    padded.resize(budget, {0u, 0u});
    move_buffer.upload(padded);
    SmcCounters counters{};
    (every_vpl ? counters.vpl_count : moves.empty() ? counters.candidate_count : counters.move_count) = count;
    auto counter_buffer = make(sizeof(SmcCounters), "counters");
    counter_buffer.upload(std::vector<SmcCounters>{counters});

    namespace shader = vplkit::shaders::smc_radiosity;
    const auto& pipeline = ctx.pipeline<shader::Pipeline>(vplkit::stages::bvh_spec<shader::Spec>(bvh));
    shader::Bindings b;
    vplkit::stages::bind_bvh(b, bvh);
    b.lights = gpu_lights.lights.descriptor();
    b.emissive = emissive.descriptor();
    b.emitter_cdf = cdf.descriptor();
    b.albedo = albedo.descriptor();
    b.records = record_buffer.descriptor();
    b.counters = counter_buffer.descriptor();
    b.moves = move_buffer.descriptor();
    shader::Push push{};
    push.budget = budget;
    push.samples = samples;
    push.sample_limit = samples + 1;
    push.bounces = bounces;
    push.step_limit = bounces + 1;
    push.punctual_count = 1;
    push.emitter_count = s.emitter ? 2 : 1;
    push.triangle_count = uint32_t(s.albedo.size());
    push.mode = every_vpl ? 2u : moves.empty() ? 0u : 1u;  // the shader's kEveryVpl, kCandidates, kMovedVpls
    vplkit::PassList passes("smc radiosity test");
    passes.add("smc radiosity", vplkit::stages::binding_uses<shader::Module>(b, {}),
               [&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, b, push, budget); });
    passes.run(ctx);
    return {record_buffer.download<SmcVpl>(budget), counter_buffer.download<SmcCounters>(1)[0].cut_short};
}

glm::dvec3 d3(const vplkit::shaders::vec3& v) {
    return {v.x, v.y, v.z};
}

// Floor [-3, 3]^2 at z = 0 (triangles 0, 1; triangle 1 black), an occluder [0.5, 1]^2 at z = 1
// (2, 3), the light at (0, 0, 2): the occluder's shadow on the floor is [1, 2]^2.
Setup occluder_setup() {
    Setup s;
    add_square(s.triangles, -3.0f, 3.0f, 0.0f, true);
    add_square(s.triangles, 0.5f, 1.0f, 1.0f, true);
    s.albedo = {{0.5f, 0.6f, 0.7f, 0.0f}, {0.0f, 0.0f, 0.0f, 0.0f}, {0.3f, 0.3f, 0.3f, 0.0f}, {0.3f, 0.3f, 0.3f, 0.0f}};
    s.light = {0.0f, 0.0f, 2.0f};
    s.intensity = {20.0f, 15.0f, 10.0f};
    return s;
}

}  // namespace

TEST_CASE("smc radiosity: one bounce equals rho I cos / d^2, zero in shadow and without reflectance") {
    const Setup s = occluder_setup();
    const auto triangles = reference_triangles(s.triangles);
    const glm::vec3 up{0.0f, 0.0f, 1.0f};
    // Triangle 0 is the floor's half below the diagonal x = y (a, b, c): points with x > y.
    std::vector<SmcVpl> records = {
        record({0.5f, -1.0f, 0.0f}, up, 0, 1),   // lit
        record({2.5f, 0.3f, 0.0f}, up, 0, 2),    // lit, grazing-ish
        record({1.6f, 1.4f, 0.0f}, up, 0, 3),    // in the occluder's shadow
        record({-1.0f, 0.5f, 0.0f}, up, 1, 4),   // black triangle
        record({0.2f, -0.1f, 0.0f}, up, 99, 5),  // no scene triangle
        record({2.9f, -2.9f, 0.0f}, up, 0, 6),   // lit, far
    };
    const uint32_t count = uint32_t(records.size());
    records.push_back(record({0.0f, -2.0f, 0.0f}, up, 0, 7));  // past the count: untouched
    const Estimated e = run(s, records, count, 4, 1);
    CHECK(e.cut_short == 0);
    for (uint32_t i = 0; i < count; ++i) {
        CAPTURE(i);
        const SmcVpl& r = records[i];
        const glm::dvec3 rho = r.triangle < s.albedo.size() ? glm::dvec3(s.albedo[r.triangle]) : glm::dvec3(0.0);
        const glm::dvec3 expected = vplkit::reference::smc_point_light_radiosity(
            d3(r.position), d3(r.normal), rho, glm::dvec3(s.light), glm::dvec3(s.intensity), triangles);
        const glm::dvec3 got = d3(e.records[i].radiosity);
        for (int c = 0; c < 3; ++c) CHECK(std::abs(got[c] - expected[c]) <= 1e-5 * expected[c]);
        CHECK(d3(e.records[i].choice_radiosity) == got);  // a candidate: the estimate that ranks it
        if (i == 0 || i == 1 || i == 5) CHECK(expected.x > 0.0);
        if (i >= 2 && i <= 4) CHECK(expected == glm::dvec3(0.0));
    }
    CHECK(e.records[count].radiosity.x == -1.0f);
}

TEST_CASE("smc radiosity: line 18 estimates only the slots the moves name and keeps their choosing estimate") {
    const Setup s = occluder_setup();
    const auto triangles = reference_triangles(s.triangles);
    const glm::vec3 up{0.0f, 0.0f, 1.0f};
    std::vector<SmcVpl> y;
    for (uint32_t i = 0; i < 8; ++i) y.push_back(record({-2.0f + 0.1f * i, -2.5f, 0.0f}, up, 0, 10 + i));
    const std::vector<std::array<uint32_t, 2>> moves = {{5, 0}, {1, 3}, {6, 2}};
    const Estimated e = run(s, y, uint32_t(moves.size()), 2, 1, moves);
    for (uint32_t i = 0; i < y.size(); ++i) {
        CAPTURE(i);
        CHECK(e.records[i].choice_radiosity.x == -2.0f);  // never rewritten on line 18
        const bool moved = i == 5 || i == 1 || i == 6;
        if (!moved) {
            CHECK(e.records[i].radiosity.x == -1.0f);
            continue;
        }
        const glm::dvec3 expected =
            vplkit::reference::smc_point_light_radiosity(d3(y[i].position), d3(y[i].normal), glm::dvec3(s.albedo[0]),
                                                         glm::dvec3(s.light), glm::dvec3(s.intensity), triangles);
        CHECK(e.records[i].radiosity.x == doctest::Approx(expected.x).epsilon(1e-5));
        CHECK(e.records[i].radiosity.z == doctest::Approx(expected.z).epsilon(1e-5));
    }
}

TEST_CASE("smc radiosity: after the light moved every VPL of Y is estimated again, both estimates") {
    Setup s = occluder_setup();
    s.light = {-1.0f, 0.5f, 1.5f};  // moved from (0, 0, 2)
    const auto triangles = reference_triangles(s.triangles);
    const glm::vec3 up{0.0f, 0.0f, 1.0f};
    std::vector<SmcVpl> y;
    for (uint32_t i = 0; i < 6; ++i) y.push_back(record({-2.0f + 0.5f * i, -1.5f + 0.2f * i, 0.0f}, up, 0, 20 + i));
    y[4].flags = 4u;  // kSmcDead: its surface moved away
    const uint32_t count = 5;
    const Estimated e = run(s, y, count, 4, 1, {}, true);
    CHECK(e.cut_short == 0);
    for (uint32_t i = 0; i < y.size(); ++i) {
        CAPTURE(i);
        if (i >= count) {
            CHECK(e.records[i].radiosity.x == -1.0f);
            CHECK(e.records[i].choice_radiosity.x == -2.0f);
            continue;
        }
        const glm::dvec3 expected = i == 4 ? glm::dvec3(0.0)
                                           : vplkit::reference::smc_point_light_radiosity(
                                                 d3(y[i].position), d3(y[i].normal), glm::dvec3(s.albedo[0]),
                                                 glm::dvec3(s.light), glm::dvec3(s.intensity), triangles);
        if (i != 4) CHECK(expected.x > 0.0);
        for (const auto& got : {d3(e.records[i].radiosity), d3(e.records[i].choice_radiosity)}) {
            for (int c = 0; c < 3; ++c) CHECK(std::abs(got[c] - expected[c]) <= 1e-5 * expected[c]);
        }
    }
}

TEST_CASE("smc radiosity: two bounces between a floor and a ceiling, mean over seeds against a quadrature") {
    Setup s;
    add_square(s.triangles, -3.0f, 3.0f, 0.0f, true);   // floor, up
    add_square(s.triangles, -3.0f, 3.0f, 2.0f, false);  // ceiling, down
    const glm::dvec3 rho_floor{0.5, 0.6, 0.7}, rho_ceiling{0.8, 0.4, 0.2};
    s.albedo = {glm::vec4(glm::vec3(rho_floor), 0.0f), glm::vec4(glm::vec3(rho_floor), 0.0f),
                glm::vec4(glm::vec3(rho_ceiling), 0.0f), glm::vec4(glm::vec3(rho_ceiling), 0.0f)};
    s.light = {0.3f, -0.2f, 1.0f};
    s.intensity = {10.0f, 10.0f, 10.0f};
    const glm::dvec3 y{0.5, -0.8, 0.0}, up{0.0, 0.0, 1.0}, light(s.light);
    const double intensity = 10.0;

    // E at y: the light directly, plus the ceiling's radiosity B_c(z) / pi = rho_c E_c(z) / pi
    // over the ceiling's solid angle.
    auto direct = [&](const glm::dvec3& p, const glm::dvec3& n) {
        const glm::dvec3 to = light - p;
        const double d2 = glm::dot(to, to);
        return intensity * std::max(glm::dot(n, to), 0.0) / std::sqrt(d2) / d2;
    };
    const int cells = 400;
    const double h = 6.0 / cells;
    double bounce = 0.0;  // integral of E_c cos_y cos_z / (pi d^2) dA, per unit rho_c
    for (int i = 0; i < cells; ++i) {
        for (int j = 0; j < cells; ++j) {
            const glm::dvec3 z{-3.0 + (i + 0.5) * h, -3.0 + (j + 0.5) * h, 2.0};
            const glm::dvec3 w = z - y;
            const double d2 = glm::dot(w, w);
            const double cosines = (w.z / std::sqrt(d2)) * (w.z / std::sqrt(d2));  // both planes horizontal
            bounce += direct(z, {0.0, 0.0, -1.0}) * cosines / (std::numbers::pi * d2) * h * h;
        }
    }
    const glm::dvec3 expected = rho_floor * (direct(y, up) + rho_ceiling * bounce);
    const double bounce_share = rho_ceiling.x * bounce / (direct(y, up) + rho_ceiling.x * bounce);
    CAPTURE(bounce_share);
    CHECK(bounce_share > 0.1);  // the second vertex matters enough for the test to see it

    for (const uint32_t n : {64u, 512u}) {
        std::vector<SmcVpl> records;
        for (uint32_t r = 0; r < n; ++r) records.push_back(record(glm::vec3(y), glm::vec3(up), 0, 1000u + 7919u * r));
        const Estimated e = run(s, records, n, 8, 2);
        CHECK(e.cut_short == 0);
        for (int c = 0; c < 3; ++c) {
            double sum = 0.0, sum2 = 0.0;
            for (const SmcVpl& r : e.records) {
                const double v = c == 0 ? r.radiosity.x : c == 1 ? r.radiosity.y : r.radiosity.z;
                sum += v;
                sum2 += v * v;
            }
            const double mean = sum / n;
            const double sigma = std::sqrt(std::max(sum2 / n - mean * mean, 0.0) * n / (n - 1));
            CAPTURE(n);
            CAPTURE(c);
            CAPTURE(mean);
            CAPTURE(expected[c]);
            CAPTURE(sigma);
            CHECK(std::abs(mean - expected[c]) <= 4.0 * sigma / std::sqrt(double(n)) + 1e-3 * expected[c]);
        }
    }
}

TEST_CASE("smc radiosity: a point light and an emissive triangle chosen by their CDF, mean against a quadrature") {
    Setup s;
    add_square(s.triangles, -3.0f, 3.0f, 0.0f, true);
    // The emitter, facing down at z = 1 (also in the BVH: its own shadow rays must pass it).
    const glm::vec3 q0{-0.5f, -0.5f, 1.0f}, q1{-0.5f, 0.5f, 1.0f}, q2{0.5f, -0.5f, 1.0f};
    s.triangles.insert(s.triangles.end(), {q0, q1, q2});
    const glm::dvec3 rho{0.5, 0.6, 0.7}, radiance{3.0, 2.0, 1.0};
    s.albedo = {glm::vec4(glm::vec3(rho), 0.0f), glm::vec4(glm::vec3(rho), 0.0f), glm::vec4(0.0f)};
    s.light = {1.0f, 1.0f, 2.0f};
    s.intensity = {10.0f, 10.0f, 10.0f};
    vplkit::shaders::EmitterTriangle e{};
    e.v0 = {q0.x, q0.y, q0.z};
    e.v1 = {q1.x, q1.y, q1.z};
    e.v2 = {q2.x, q2.y, q2.z};
    e.triangle = 2;
    e.area = 0.5f;
    e.radiance = {3.0f, 2.0f, 1.0f};
    s.emitter = e;
    s.light_share = 0.4f;
    const glm::dvec3 y{0.3, -0.2, 0.0}, up{0.0, 0.0, 1.0};

    // The triangle's irradiance at y: cells of a regular N^2 subdivision, each at its centroid.
    const glm::dvec3 a(q0), b(q1), c(q2), nq{0.0, 0.0, -1.0};
    const int cells = 300;
    double emitted = 0.0;
    for (int i = 0; i < cells; ++i) {
        for (int j = 0; i + j < cells; ++j) {
            // The upright cell (i, j) and, where it exists, the inverted one beside it.
            for (int flip = 0; flip < 2; ++flip) {
                if (flip == 1 && i + j + 1 >= cells) continue;
                const double u = (i + (flip == 0 ? 1.0 / 3.0 : 2.0 / 3.0)) / cells;
                const double v = (j + (flip == 0 ? 1.0 / 3.0 : 2.0 / 3.0)) / cells;
                const glm::dvec3 q = a + u * (b - a) + v * (c - a);
                const glm::dvec3 w = q - y;
                const double d2 = glm::dot(w, w);
                const double cos_y = glm::dot(up, w) / std::sqrt(d2), cos_q = -glm::dot(nq, w) / std::sqrt(d2);
                emitted += cos_y * cos_q / d2 * (0.5 / (double(cells) * cells));
            }
        }
    }
    const auto triangles = reference_triangles(s.triangles);
    const glm::dvec3 expected = vplkit::reference::smc_point_light_radiosity(y, up, rho, glm::dvec3(s.light),
                                                                             glm::dvec3(s.intensity), triangles) +
                                rho * radiance * emitted;
    for (const uint32_t n : {64u, 512u}) {
        std::vector<SmcVpl> records;
        for (uint32_t r = 0; r < n; ++r) records.push_back(record(glm::vec3(y), glm::vec3(up), 0, 77u + 104729u * r));
        const Estimated est = run(s, records, n, 8, 1);
        CHECK(est.cut_short == 0);
        for (int ch = 0; ch < 3; ++ch) {
            double sum = 0.0, sum2 = 0.0;
            for (const SmcVpl& r : est.records) {
                const double v = ch == 0 ? r.radiosity.x : ch == 1 ? r.radiosity.y : r.radiosity.z;
                sum += v;
                sum2 += v * v;
            }
            const double mean = sum / n;
            const double sigma = std::sqrt(std::max(sum2 / n - mean * mean, 0.0) * n / (n - 1));
            CAPTURE(n);
            CAPTURE(ch);
            CAPTURE(mean);
            CAPTURE(expected[ch]);
            CAPTURE(sigma);
            CHECK(sigma > 0.0);  // two emitters: the choice varies
            CHECK(std::abs(mean - expected[ch]) <= 4.0 * sigma / std::sqrt(double(n)) + 1e-3 * expected[ch]);
        }
    }
}
