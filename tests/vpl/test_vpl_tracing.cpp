// trace_vpls.comp (instant radiosity) against analytic answers.
//
// The closed-box identity: in a closed enclosure whose every surface reflects diffusely with
// albedo rho, all the flux Phi the emitters put out lands on a surface, a fraction rho of it is
// reflected and lands again, and so on: the flux reflected at the k-th surface interaction is
// Phi * rho^k per channel, whatever the shape. The VPLs of bounce k carry, summed, an unbiased
// estimate of it. Tolerance of such a check: |mean over n seeds - exact| <= 4 sigma / sqrt(n)
// (sigma: the seeds' sample standard deviation; 4 sigma leaves a chance of ~1e-4 of a false
// failure per check) plus 2e-4 relative for float accumulation (the first bounce of a point light
// in a grey box has no variance at all: every path deposits exactly Phi rho / N).
//
// Geometry checks (every VPL finite, on a surface, unit normal facing the arriving light) use a
// CPU point-to-triangle distance in double; a hit point from barycentrics is off by a few ulps of
// the coordinates, so 1e-5 of the scene's size is generous.

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/vpl_tracing_buffers.hpp"
#include "vplkit_test/context.hpp"
#include "brsm_reference.hpp"
#include "geometry_reference.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>
#include <vector>

namespace {

using vplkit::scene::Scene;
using vplkit::stages::VplTracingOptions;
constexpr double kPi = std::numbers::pi;

uint32_t add_material(Scene& scene, glm::vec3 rho, float metallic = 0.0f) {
    vplkit::scene::Material m;
    m.base_color_factor = glm::vec4(rho, 1.0f);
    m.metallic_factor = metallic;
    scene.materials.push_back(m);
    return uint32_t(scene.materials.size() - 1);
}

void add_triangle(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material) {
    for (glm::vec3 p : {a, b, c}) {
        vplkit::scene::Vertex v;
        v.position = p;
        v.normal = glm::normalize(glm::cross(b - a, c - a));
        scene.indices.push_back(uint32_t(scene.vertices.size()));
        scene.vertices.push_back(v);
    }
    scene.triangle_materials.push_back(material);
    if (scene.materials[material].emits())
        scene.emissive_triangles.push_back(uint32_t(scene.triangle_materials.size() - 1));
}

void add_quad(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material) {
    add_triangle(scene, a, b, c, material);
    add_triangle(scene, a, c, d, material);
}

// The six faces of [lo, hi], each split in two triangles (windings mixed on purpose: light is
// two-sided for the tracer).
void add_box(Scene& scene, glm::vec3 lo, glm::vec3 hi, uint32_t material) {
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    add_quad(scene, c[0], c[1], c[2], c[3], material);
    add_quad(scene, c[4], c[5], c[6], c[7], material);
    add_quad(scene, c[0], c[1], c[5], c[4], material);
    add_quad(scene, c[3], c[2], c[6], c[7], material);
    add_quad(scene, c[0], c[3], c[7], c[4], material);
    add_quad(scene, c[1], c[2], c[6], c[5], material);
}

const glm::vec3 kBoxLo{-1.0f, -0.75f, -0.5f}, kBoxHi{1.0f, 0.75f, 0.5f};

vplkit::scene::Light point_light(glm::vec3 position, glm::vec3 color, float intensity) {
    vplkit::scene::Light l;
    l.type = vplkit::scene::LightType::point;
    l.position = position;
    l.color = color;
    l.intensity = intensity;
    return l;
}

struct Traced {
    std::vector<vplkit::shaders::Vpl> vpls;
    std::vector<uint32_t> bounces;
};

// Traces `scene` with `options`; the BVH's ids are the scene's triangle indices.
class Tracer {
public:
    explicit Tracer(const Scene& scene)
        : bvh_(
              vplkit::upload_bvh(vplkit::test::context(), vplkit::build_bvh(vplkit::scene::triangle_positions(scene)))),
          sources_(vplkit::upload_vpl_sources(vplkit::test::context(), scene)) {}

    Traced run(const VplTracingOptions& options) {
        vplkit::Context& ctx = vplkit::test::context();
        auto output = vplkit::VplTracingOutput::create(ctx, options);
        vplkit::PassList passes("vpl tracing test");
        vplkit::stages::add_trace_vpls_pass(ctx, passes, bvh_, sources_, options, output);
        passes.run(ctx);
        const auto counts = vplkit::download_vpl_counts(output);
        // Short paths stay far below lavapipe's loop limit: none may be reported cut.
        REQUIRE(counts.cut_short == 0);
        const uint32_t count = vplkit::download_vpl_count(output);
        REQUIRE(count == counts.vpls);
        REQUIRE(count <= output.capacity);
        Traced t;
        if (count > 0) {
            t.vpls = output.vpls.download<vplkit::shaders::Vpl>(count);
            t.bounces = output.bounces.download<uint32_t>(count);
        }
        return t;
    }

    const vplkit::VplSources& sources() const { return sources_; }
    const vplkit::GpuBvh& bvh() const { return bvh_; }

private:
    vplkit::GpuBvh bvh_;
    vplkit::VplSources sources_;
};

using Rgb = std::array<double, 3>;

// Per bounce 1..max_bounces: the summed VPL flux (index 0 unused).
std::vector<Rgb> flux_per_bounce(const Traced& t, uint32_t max_bounces) {
    std::vector<Rgb> sums(max_bounces + 1, Rgb{0, 0, 0});
    for (size_t i = 0; i < t.vpls.size(); ++i) {
        REQUIRE(t.bounces[i] >= 1);
        REQUIRE(t.bounces[i] <= max_bounces);
        sums[t.bounces[i]][0] += t.vpls[i].flux.x;
        sums[t.bounces[i]][1] += t.vpls[i].flux.y;
        sums[t.bounces[i]][2] += t.vpls[i].flux.z;
    }
    return sums;
}

// Mean over seeds of the per-bounce flux against expected[k] (k = 1..max_bounces), per channel.
void check_mean_flux(Tracer& tracer, VplTracingOptions options, uint32_t seeds, const std::vector<Rgb>& expected) {
    std::vector<std::vector<Rgb>> runs;
    for (uint32_t s = 0; s < seeds; ++s) {
        options.seed = 1000 + 17 * s;
        runs.push_back(flux_per_bounce(tracer.run(options), options.max_bounces));
    }
    for (uint32_t k = 1; k <= options.max_bounces; ++k) {
        for (int c = 0; c < 3; ++c) {
            double mean = 0.0;
            for (const auto& r : runs) mean += r[k][c];
            mean /= seeds;
            double var = 0.0;
            for (const auto& r : runs) var += (r[k][c] - mean) * (r[k][c] - mean);
            const double sigma = std::sqrt(var / (seeds - 1));
            const double bound = 4.0 * sigma / std::sqrt(double(seeds)) + 2e-4 * expected[k][c];
            CAPTURE(k);
            CAPTURE(c);
            CAPTURE(mean);
            CAPTURE(expected[k][c]);
            CAPTURE(sigma);
            CHECK(std::abs(mean - expected[k][c]) <= bound);
        }
    }
}

bool finite(const vplkit::shaders::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::dvec3 to_d(const vplkit::shaders::vec3& v) {
    return {v.x, v.y, v.z};
}

// Spot power by midpoint quadrature of lights.glsl's squared angular attenuation over the sphere
// (independent of the closed form upload_vpl_sources uses).
double spot_power_per_intensity(float inner, float outer) {
    const double cos_inner = std::cos(double(inner)), cos_outer = std::cos(double(outer));
    const double s = 1.0 / std::max(0.001, cos_inner - cos_outer), o = -cos_outer * s;
    const int steps = 200000;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double c = -1.0 + 2.0 * (i + 0.5) / steps;
        const double a = std::clamp(c * s + o, 0.0, 1.0);
        sum += a * a;
    }
    return 2.0 * kPi * sum * 2.0 / steps;
}

}  // namespace

TEST_CASE("vpl tracing: closed box with a point light reflects Phi rho^k at bounce k") {
    for (glm::vec3 rho : {glm::vec3(0.5f), glm::vec3(0.8f, 0.5f, 0.2f)}) {
        CAPTURE(rho.x);
        CAPTURE(rho.z);
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, rho));
        const glm::vec3 color{1.0f, 0.8f, 0.6f};
        const float intensity = 3.0f;
        scene.lights.push_back(point_light({0.3f, 0.1f, -0.2f}, color, intensity));
        Tracer tracer(scene);
        const uint32_t max_bounces = 4;
        std::vector<Rgb> expected(max_bounces + 1);
        for (uint32_t k = 1; k <= max_bounces; ++k) {
            for (int c = 0; c < 3; ++c) {
                expected[k][c] = 4.0 * kPi * intensity * color[c] * std::pow(double(rho[c]), double(k));
            }
        }
        check_mean_flux(tracer, {4000, max_bounces, 0}, 12, expected);
    }
}

TEST_CASE("vpl tracing: closed box with a spot light a point light and a double-sided emissive triangle") {
    const float rho = 0.6f;
    Scene scene;
    add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(rho)));
    // A floating emitter that also reflects with rho: the enclosure is still all albedo rho.
    const uint32_t glow = add_material(scene, glm::vec3(rho));
    scene.materials[glow].emissive_factor = {1.0f, 0.5f, 0.25f};
    scene.materials[glow].emissive_strength = 2.0f;
    scene.materials[glow].double_sided = true;
    const glm::vec3 ta{-0.5f, -0.2f, 0.1f}, tb{-0.1f, -0.3f, 0.2f}, tc{-0.3f, 0.2f, -0.1f};
    add_triangle(scene, ta, tb, tc, glow);
    vplkit::scene::Light spot;
    spot.type = vplkit::scene::LightType::spot;
    spot.position = {0.5f, 0.4f, 0.0f};
    spot.direction = glm::normalize(glm::vec3(-0.5f, -1.0f, 0.3f));
    spot.color = {0.2f, 1.0f, 0.5f};
    spot.intensity = 6.0f;
    spot.inner_cone_angle = 0.3f;
    spot.outer_cone_angle = 0.7f;
    scene.lights.push_back(spot);
    scene.lights.push_back(point_light({0.6f, -0.3f, 0.2f}, {1.0f, 1.0f, 1.0f}, 0.5f));

    const double area = 0.5 * glm::length(glm::cross(glm::dvec3(tb - ta), glm::dvec3(tc - ta)));
    const double spot_factor = spot_power_per_intensity(spot.inner_cone_angle, spot.outer_cone_angle);
    Rgb phi{};
    for (int c = 0; c < 3; ++c) {
        phi[c] = spot_factor * spot.intensity * spot.color[c] + 4.0 * kPi * 0.5 +
                 2.0 * kPi * area * 2.0 * scene.materials[glow].emissive_factor[c];
    }
    Tracer tracer(scene);
    for (int c = 0; c < 3; ++c) CHECK(tracer.sources().total_power[c] == doctest::Approx(phi[c]).epsilon(1e-4));
    // The selection CDF: emitters in order spot, point, triangle, each picked in proportion to
    // its power summed over RGB; the last entry exactly 1.
    REQUIRE(tracer.sources().emitter_count == 3);
    const auto cdf = tracer.sources().emitter_cdf.download<float>(3);
    const double spot_w = spot_factor * spot.intensity * (0.2 + 1.0 + 0.5), point_w = 3.0 * 4.0 * kPi * 0.5,
                 glow_w = 2.0 * kPi * area * 2.0 * (1.0 + 0.5 + 0.25), total_w = spot_w + point_w + glow_w;
    CHECK(cdf[0] == doctest::Approx(spot_w / total_w).epsilon(1e-4));
    CHECK(cdf[1] - cdf[0] == doctest::Approx(point_w / total_w).epsilon(1e-4));
    CHECK(cdf[2] == 1.0f);
    const uint32_t max_bounces = 3;
    std::vector<Rgb> expected(max_bounces + 1);
    for (uint32_t k = 1; k <= max_bounces; ++k) {
        for (int c = 0; c < 3; ++c) expected[k][c] = phi[c] * std::pow(double(rho), double(k));
    }
    check_mean_flux(tracer, {4000, max_bounces, 0}, 16, expected);
}

TEST_CASE("vpl tracing: every VPL is finite and on a surface with a unit normal facing the light") {
    Scene scene;
    add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.7f, 0.6f, 0.5f)));
    scene.lights.push_back(point_light({-0.4f, 0.2f, 0.1f}, {1.0f, 1.0f, 1.0f}, 2.0f));
    Tracer tracer(scene);
    const Traced t = tracer.run({3000, 5, 7});
    REQUIRE(t.vpls.size() >= 3000);
    const auto positions = vplkit::scene::triangle_positions(scene);
    const glm::dvec3 center = (glm::dvec3(kBoxLo) + glm::dvec3(kBoxHi)) * 0.5;
    int failures = 0;
    for (size_t i = 0; i < t.vpls.size() && failures < 5; ++i) {
        const auto& v = t.vpls[i];
        CAPTURE(i);
        bool ok = finite(v.position) && finite(v.normal) && finite(v.flux);
        const glm::dvec3 p = to_d(v.position), n = to_d(v.normal);
        ok = ok && std::abs(glm::length(n) - 1.0) < 1e-5;
        ok = ok && v.flux.x > 0 && v.flux.y > 0 && v.flux.z > 0;
        double nearest = 1e30;
        glm::dvec3 face{0.0};
        for (size_t k = 0; k < positions.size(); k += 3) {
            const glm::dvec3 a(positions[k]), b(positions[k + 1]), c(positions[k + 2]);
            const double d = vplkit::reference::point_triangle_distance(p, a, b, c);
            if (d < nearest) {
                nearest = d;
                face = glm::normalize(glm::cross(b - a, c - a));
            }
        }
        CAPTURE(nearest);
        ok = ok && nearest <= 1e-5;
        // The face normal, turned to the inside of the box (where all the light comes from).
        ok = ok && std::abs(std::abs(glm::dot(n, face)) - 1.0) < 1e-5 && glm::dot(n, center - p) > 0.0;
        if (!ok) ++failures;
        CHECK(ok);
    }
}

TEST_CASE("vpl tracing: the same seed gives the same VPLs and another seed other ones") {
    Scene scene;
    add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.5f)));
    scene.lights.push_back(point_light({0.1f, 0.2f, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
    Tracer tracer(scene);
    // The members (not the padding, which nothing writes), in buffer order.
    auto in_order = [](const Traced& t) {
        std::vector<std::tuple<uint32_t, float, float, float, float, float, float, float, float, float>> v;
        for (size_t i = 0; i < t.vpls.size(); ++i) {
            const auto& x = t.vpls[i];
            v.emplace_back(t.bounces[i], x.position.x, x.position.y, x.position.z, x.normal.x, x.normal.y, x.normal.z,
                           x.flux.x, x.flux.y, x.flux.z);
        }
        return v;
    };
    auto sorted = [&](const Traced& t) {
        auto v = in_order(t);
        std::sort(v.begin(), v.end());
        return v;
    };
    const Traced first = tracer.run({2000, 3, 42});
    const Traced again = tracer.run({2000, 3, 42});
    // The same VPLs in the same order, bit for bit (the order is fixed by the seed: see the next case).
    CHECK(in_order(first) == in_order(again));
    const auto a = sorted(first);
    const auto c = sorted(tracer.run({2000, 3, 43}));
    REQUIRE(!a.empty());
    CHECK(a != c);
    // Not merely a reordering: the first-bounce positions differ.
    size_t same = 0;
    for (const auto& x : c) same += std::binary_search(a.begin(), a.end(), x) ? 1 : 0;
    CHECK(same < c.size() / 100);
}

namespace {

// Where path `path` of trace_vpls.comp, from the only emitter, a point light at `light` inside the
// box [lo, hi], first meets the box: the shader's random numbers (PCG32 stream `path` under
// `seed`: the emitter's number, then u.x, u.y of sample_uniform_sphere), the ray in double.
struct BoxHit {
    glm::dvec3 position{0.0};
    glm::dvec3 normal{0.0};      // the face's, facing the light (the inside)
    double edge_distance = 0.0;  // to the nearest edge of the face
};
BoxHit first_box_hit(vplkit::reference::Pcg32& rng, glm::dvec3 light, glm::dvec3 lo, glm::dvec3 hi) {
    rng.next_float();  // which emitter: there is one
    const double ux = rng.next_float(), uy = rng.next_float();
    const double z = 1.0 - 2.0 * ux, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * uy;
    const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
    int axis = -1;
    double t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) continue;
        const double ta = ((d[a] > 0.0 ? hi[a] : lo[a]) - light[a]) / d[a];
        if (ta < t) t = ta, axis = a;
    }
    BoxHit h;
    h.position = light + t * d;
    h.normal[axis] = d[axis] > 0.0 ? -1.0 : 1.0;
    h.edge_distance = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (a == axis) continue;
        h.edge_distance = std::min({h.edge_distance, h.position[a] - lo[a], hi[a] - h.position[a]});
    }
    return h;
}

}  // namespace

// Before the VPLs were packed by path (trace_vpls.comp appended each at atomicAdd(count, 1)),
// this failed: the invocations of a SIMD batch appended their first hits together, then their
// second ones, and the batches landed in the order the driver's threads ran them.
TEST_CASE("vpl tracing: the VPLs come out by path then bounce, in the order of a CPU trace of the same paths") {
    const float rho = 0.7f;
    Scene scene;
    add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(rho)));
    const glm::vec3 light{0.3f, 0.1f, -0.2f};
    const float intensity = 3.0f;
    scene.lights.push_back(point_light(light, {1.0f, 1.0f, 1.0f}, intensity));
    Tracer tracer(scene);
    // 1000 paths: four blocks of the packing (256 paths each), the last one partial.
    const VplTracingOptions options{1000, 3, 77};
    const Traced t = tracer.run(options);

    // The CPU trace. In the closed box every path hits a wall first (a VPL, rho > 0); Russian
    // roulette then goes on while its number is below q = rho (grey: beta * rho / q keeps beta), up
    // to max_bounces hits. Between two roulette numbers the path draws its bounce direction (two).
    std::vector<uint32_t> bounces;
    std::vector<BoxHit> first_hits;
    for (uint32_t path = 0; path < options.paths; ++path) {
        vplkit::reference::Pcg32 rng(options.seed, path);
        first_hits.push_back(first_box_hit(rng, light, kBoxLo, kBoxHi));
        uint32_t hits = 1;
        while (hits < options.max_bounces && rng.next_float() < double(rho)) {
            rng.next_float();
            rng.next_float();
            ++hits;
        }
        for (uint32_t k = 1; k <= hits; ++k) bounces.push_back(k);
    }
    // Element by element, in order: the bounces say where each path's VPLs begin.
    REQUIRE(t.bounces == bounces);
    const double phi_per_path = 4.0 * kPi * intensity / options.paths;
    size_t path = 0, checked_normals = 0;
    for (size_t i = 0; i < t.vpls.size(); ++i) {
        CAPTURE(i);
        const auto& v = t.vpls[i];
        // Flux Phi / N rho at every bounce (roulette's beta * rho / q keeps beta in a grey box):
        // a few float products, so 1e-5 relative is a few ulps.
        const double flux = phi_per_path * double(rho);
        CHECK(v.flux.x == doctest::Approx(flux).epsilon(1e-5));
        CHECK(v.flux.z == doctest::Approx(flux).epsilon(1e-5));
        if (t.bounces[i] != 1) continue;
        const BoxHit& h = first_hits[path++];
        CAPTURE(path);
        // The float ray and BVH against the double ray: 1e-5 of the box's size (2) is generous.
        CHECK(glm::distance(to_d(v.position), h.position) <= 2e-5);
        // At an edge the shader may take either face: its normal is checked away from them.
        if (h.edge_distance > 1e-4) {
            CHECK(glm::dot(to_d(v.normal), h.normal) > 1.0 - 1e-5);
            ++checked_normals;
        }
    }
    CHECK(path == options.paths);
    CHECK(checked_normals > options.paths * 9 / 10);
}

TEST_CASE("vpl tracing: Russian roulette and the bounce limit") {
    SUBCASE("albedo 1: every path survives to max_bounces") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(1.0f)));
        scene.lights.push_back(point_light({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
        Tracer tracer(scene);
        const uint32_t paths = 1000, max_bounces = 6;
        const Traced t = tracer.run({paths, max_bounces, 3});
        CHECK(t.vpls.size() == size_t(paths) * max_bounces);
        std::vector<uint32_t> per_bounce(max_bounces + 1, 0);
        for (uint32_t b : t.bounces) {
            REQUIRE(b >= 1);
            REQUIRE(b <= max_bounces);
            ++per_bounce[b];
        }
        for (uint32_t k = 1; k <= max_bounces; ++k) CHECK(per_bounce[k] == paths);
        // Lossless: every bounce re-emits all of Phi.
        const auto sums = flux_per_bounce(t, max_bounces);
        for (uint32_t k = 1; k <= max_bounces; ++k) CHECK(sums[k][0] == doctest::Approx(4.0 * kPi).epsilon(2e-4));
    }
    SUBCASE("albedo 0.4: the number of bounce-k VPLs is binomial with survival 0.4^(k-1)") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.4f, 0.1f, 0.3f)));
        scene.lights.push_back(point_light({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
        Tracer tracer(scene);
        const uint32_t paths = 4000, max_bounces = 3;
        const Traced t = tracer.run({paths, max_bounces, 9});
        std::vector<double> per_bounce(max_bounces + 1, 0);
        for (uint32_t b : t.bounces) {
            REQUIRE(b >= 1);
            REQUIRE(b <= max_bounces);
            ++per_bounce[b];
        }
        for (uint32_t k = 1; k <= max_bounces; ++k) {
            // q = max(rho) = 0.4 decides survival, whatever the other channels.
            const double p = std::pow(0.4, double(k - 1));
            const double mean = paths * p, sigma = std::sqrt(paths * p * (1.0 - p));
            CAPTURE(k);
            CHECK(std::abs(per_bounce[k] - mean) <= 5.0 * sigma + 0.5);
        }
    }
}

TEST_CASE("vpl tracing: a directional light over a plane reflects E A cos rho at the first bounce") {
    const float rho = 0.6f;
    Scene scene;
    const uint32_t m = add_material(scene, glm::vec3(rho));
    const float w = 2.0f, d = 3.0f;  // plane y = 0, [0, w] x [0, d]
    add_quad(scene, {0, 0, 0}, {0, 0, d}, {w, 0, d}, {w, 0, 0}, m);
    vplkit::scene::Light sun;
    sun.type = vplkit::scene::LightType::directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.color = {1.0f, 0.75f, 0.5f};
    sun.intensity = 2.0f;
    scene.lights.push_back(sun);
    Tracer tracer(scene);
    const double cos_theta = -double(sun.direction.y);
    std::vector<Rgb> expected(3, Rgb{0, 0, 0});  // bounce 2: light leaving the plane escapes
    for (int c = 0; c < 3; ++c) expected[1][c] = double(sun.intensity) * sun.color[c] * w * d * cos_theta * rho;
    check_mean_flux(tracer, {3000, 2, 0}, 12, expected);
    const Traced t = tracer.run({3000, 2, 5});
    CHECK(std::count(t.bounces.begin(), t.bounces.end(), 2u) == 0);
    for (const auto& v : t.vpls) {
        REQUIRE(std::abs(v.position.y) <= 1e-5f);
        REQUIRE(v.normal.y == doctest::Approx(1.0f));  // facing the sun, whatever the winding
    }
}

TEST_CASE("vpl tracing: no VPLs without light or without diffuse reflectance") {
    SUBCASE("no lights") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.5f)));
        Tracer tracer(scene);
        CHECK(tracer.sources().emitter_count == 0);
        CHECK(tracer.run({500, 3, 1}).vpls.empty());
    }
    SUBCASE("black light") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.5f)));
        scene.lights.push_back(point_light({0, 0, 0}, {0, 0, 0}, 1.0f));
        Tracer tracer(scene);
        CHECK(tracer.run({500, 3, 1}).vpls.empty());
    }
    SUBCASE("metal walls have no diffuse reflectance") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.9f), 1.0f));
        scene.lights.push_back(point_light({0, 0, 0}, {1, 1, 1}, 1.0f));
        Tracer tracer(scene);
        CHECK(tracer.run({500, 3, 1}).vpls.empty());
    }
    SUBCASE("a zero-weight light beside a bright one is never chosen") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.5f)));
        scene.lights.push_back(point_light({0.2f, 0, 0}, {1, 1, 1}, 1.0f));
        scene.lights.push_back(point_light({-0.2f, 0, 0}, {0, 0, 0}, 1.0f));
        Tracer tracer(scene);
        const Traced t = tracer.run({2000, 1, 4});
        CHECK(t.vpls.size() == 2000);
        for (const auto& v : t.vpls) REQUIRE(v.flux.x == doctest::Approx(4.0 * kPi * 0.5 / 2000).epsilon(1e-4));
    }
}

TEST_CASE("vpl tracing: boxes at 1e-3 and 1e4 scale neither leak nor lose flux") {
    for (float scale : {1e-3f, 1e4f}) {
        CAPTURE(scale);
        Scene scene;
        add_box(scene, kBoxLo * scale, kBoxHi * scale, add_material(scene, glm::vec3(0.5f)));
        // A corner of the box is where offsets matter most: light near it.
        scene.lights.push_back(point_light(glm::vec3(0.95f, 0.7f, 0.45f) * scale, {1.0f, 1.0f, 1.0f}, 1.0f));
        Tracer tracer(scene);
        const Traced t = tracer.run({3000, 3, 11});
        const auto sums = flux_per_bounce(t, 3);
        // Every path reaches a wall: bounce 1 is exactly Phi rho (see the file's header).
        CHECK(sums[1][0] == doctest::Approx(4.0 * kPi * 0.5).epsilon(2e-4));
        size_t second = std::count(t.bounces.begin(), t.bounces.end(), 2u);
        // Binomial(3000, 0.5): 5 sigma.
        CHECK(std::abs(double(second) - 1500.0) <= 5.0 * std::sqrt(750.0));
        for (const auto& v : t.vpls) {
            const glm::dvec3 p = to_d(v.position) / double(scale);
            const glm::dvec3 lo(kBoxLo), hi(kBoxHi);
            const double inside = std::min({p.x - lo.x, hi.x - p.x, p.y - lo.y, hi.y - p.y, p.z - lo.z, hi.z - p.z});
            REQUIRE(std::abs(inside) <= 1e-5);  // on a wall, relative to the box's size
        }
    }
}

TEST_CASE("vpl tracing: textures enter the reflectance as their means") {
    Scene scene;
    const uint32_t m = add_material(scene, glm::vec3(0.9f, 0.8f, 1.0f));
    // Base colour: two texels, sRGB 255 and 128 in R, 0 and 255 in G, 64 in B.
    vplkit::scene::Image colour;
    colour.width = 2;
    colour.height = 1;
    colour.rgba = {255, 0, 64, 255, 128, 255, 64, 255};
    colour.srgb = true;
    // Metallic (B): 255 and 0, so the mean metallic is 0.5 x metallic_factor.
    vplkit::scene::Image metal;
    metal.width = 1;
    metal.height = 2;
    metal.rgba = {0, 200, 255, 255, 0, 100, 0, 255};
    metal.linear = true;
    scene.images = {colour, metal};
    scene.textures.resize(2);
    scene.textures[0].image = 0;
    scene.textures[1].image = 1;
    scene.materials[m].base_color_texture = 0;
    scene.materials[m].metallic_roughness_texture = 1;
    scene.materials[m].metallic_factor = 0.4f;
    add_box(scene, kBoxLo, kBoxHi, m);
    scene.lights.push_back(point_light({0.1f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
    auto linear = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
    const double diffuse = 1.0 - 0.4 * 0.5;
    const Rgb rho = {0.9 * 0.5 * (linear(1.0) + linear(128 / 255.0)) * diffuse, 0.8 * 0.5 * linear(1.0) * diffuse,
                     1.0 * linear(64 / 255.0) * diffuse};
    Tracer tracer(scene);
    // One bounce of one point light: every path deposits Phi rho / N, no variance.
    const auto sums = flux_per_bounce(tracer.run({1000, 1, 2}), 1);
    for (int c = 0; c < 3; ++c) {
        CAPTURE(c);
        CHECK(sums[1][c] == doctest::Approx(4.0 * kPi * rho[c]).epsilon(2e-4));
    }
}

TEST_CASE("vpl tracing: an alpha-tested material reflects the mean of the texels it keeps") {
    // Rays pass where alpha x the factor's alpha < cutoff (bvh.glsl), so a light path only hits
    // the kept texels: their mean, not the whole texture's, is what a hit reflects. Texels (sRGB
    // R, G, B, A): white opaque, black transparent, grey half-covered (alpha 128: kept at cutoff
    // 0.5 with factor alpha 1, dropped with factor alpha 0.9). Expected by hand, to float
    // rounding of the host's double arithmetic (1e-6).
    auto linear = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
    struct Case {
        vplkit::scene::AlphaMode mode;
        float cutoff;
        float factor_alpha;
        double expected;  // every channel
    };
    const double grey = linear(100 / 255.0);
    for (const Case c : {Case{vplkit::scene::AlphaMode::mask, 0.5f, 1.0f, (1.0 + grey) / 2.0},
                         Case{vplkit::scene::AlphaMode::mask, 0.5f, 0.9f, 1.0},
                         Case{vplkit::scene::AlphaMode::blend, 0.9f, 1.0f, (1.0 + grey) / 2.0},
                         Case{vplkit::scene::AlphaMode::opaque, 0.5f, 1.0f, (1.0 + grey) / 3.0}}) {
        CAPTURE(int(c.mode));
        CAPTURE(c.factor_alpha);
        Scene scene;
        const uint32_t m = add_material(scene, glm::vec3(1.0f));
        vplkit::scene::Image colour;
        colour.width = 3;
        colour.height = 1;
        colour.rgba = {255, 255, 255, 255, 0, 0, 0, 0, 100, 100, 100, 128};
        colour.srgb = true;
        scene.images = {colour};
        scene.textures.resize(1);
        scene.materials[m].base_color_texture = 0;
        scene.materials[m].base_color_factor.a = c.factor_alpha;
        scene.materials[m].alpha_mode = c.mode;
        scene.materials[m].alpha_cutoff = c.cutoff;  // blend: 0.5 whatever the file says
        add_triangle(scene, {0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, m);
        scene.lights.push_back(point_light({0.2f, 0.2f, 1.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
        const auto sources = vplkit::upload_vpl_sources(vplkit::test::context(), scene);
        const auto albedo = sources.triangle_albedo.template download<vplkit::shaders::vec4>(1);
        CHECK(std::abs(albedo[0].x - c.expected) <= 1e-6);
        CHECK(std::abs(albedo[0].y - c.expected) <= 1e-6);
        CHECK(std::abs(albedo[0].z - c.expected) <= 1e-6);
    }
}

TEST_CASE("vpl tracing: paths a driver cuts short are counted and refused never silently lost") {
    // Albedo 1: no path ends before max_bounces, and 20000 bounces x several traversal steps pass
    // lavapipe's 65535 loop iterations; a driver without that limit traces them all.
    Scene scene;
    add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(1.0f)));
    scene.lights.push_back(point_light({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
    Tracer tracer(scene);
    vplkit::Context& ctx = vplkit::test::context();
    const VplTracingOptions options{16, 20000, 1};
    auto output = vplkit::VplTracingOutput::create(ctx, options);
    vplkit::PassList passes("vpl tracing cut short");
    vplkit::stages::add_trace_vpls_pass(ctx, passes, tracer.bvh(), tracer.sources(), options, output);
    passes.run(ctx);
    const auto counts = vplkit::download_vpl_counts(output);
    MESSAGE("cut short: " << counts.cut_short << " of 16 paths, " << counts.vpls << " VPLs");
    if (counts.cut_short == 0) {
        CHECK(counts.vpls == 16u * 20000u);
        CHECK(vplkit::download_vpl_count(output) == counts.vpls);
    } else {
        CHECK(counts.vpls < 16u * 20000u);
        CHECK_THROWS_AS(vplkit::download_vpl_count(output), vplkit::Error);
    }
}

TEST_CASE("vpl tracing: invalid options are refused") {
    CHECK_THROWS_AS(vplkit::stages::vpl_capacity({0, 3, 0}), vplkit::Error);
    CHECK_THROWS_AS(vplkit::stages::vpl_capacity({10, 0, 0}), vplkit::Error);
    CHECK_THROWS_AS(vplkit::stages::vpl_capacity({0x10000u, 0x10000u, 0}), vplkit::Error);
    CHECK_THROWS_AS(vplkit::stages::vpl_capacity({1, 0xffffffffu, 0}), vplkit::Error);
    CHECK(vplkit::stages::vpl_capacity({1000, 3, 0}) == 3000);
    Scene empty;
    CHECK_THROWS_AS(vplkit::upload_vpl_sources(vplkit::test::context(), empty), vplkit::Error);
}
