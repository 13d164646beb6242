// update_pose's BVH: refitted on the GPU while the tree's SAH cost holds, rebuilt when a motion
// scatters its leaves (the cost past kBvhRebuildCostRatio times its build's), and the frame traced
// through either equal to a renderer's made on the moved scene.

#include "vplkit/bvh_gpu_build.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

namespace {

namespace scene = vplkit::scene;

// A grid of `n` x `n` separate quads (4 vertices each) over [-1, 1]^2 at z = 0, an occluder quad
// at z = 0.5 over [-0.3, 0.3]^2 (the last two triangles), a point light above.
scene::Scene grid_scene(uint32_t n) {
    scene::Scene s;
    scene::Material grey;
    grey.name = "grey";
    grey.base_color_factor = {0.8f, 0.8f, 0.8f, 1.0f};
    grey.metallic_factor = 0.0f;
    s.materials.push_back(grey);
    auto quad = [&s](glm::vec3 lo, glm::vec3 hi) {
        const uint32_t base = uint32_t(s.vertices.size());
        for (glm::vec3 p : {lo, glm::vec3(hi.x, lo.y, lo.z), hi, glm::vec3(lo.x, hi.y, lo.z)}) {
            scene::Vertex v;
            v.position = p;
            v.normal = {0.0f, 0.0f, 1.0f};
            s.vertices.push_back(v);
            s.vertex_random.push_back(uint32_t(s.vertices.size()));
        }
        s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        s.triangle_materials.insert(s.triangle_materials.end(), 2, 0u);
    };
    const float step = 2.0f / float(n);
    for (uint32_t y = 0; y < n; ++y) {
        for (uint32_t x = 0; x < n; ++x) {
            const glm::vec3 lo{-1.0f + step * x, -1.0f + step * y, 0.0f};
            quad(lo, lo + glm::vec3(step, step, 0.0f));
        }
    }
    quad({-0.3f, -0.3f, 0.5f}, {0.3f, 0.3f, 0.5f});
    scene::Light light;
    light.position = {0.2f, 0.1f, 2.0f};
    light.intensity = 4.0f;
    s.lights.push_back(light);
    s.bounds = {{-1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.5f}};
    return s;
}

void translate(scene::Scene& s, glm::vec3 by) {
    for (scene::Vertex& v : s.vertices) v.position += by;
}

// Moves the first `quads` grid quads to each other's places in a random order (a fixed shuffle):
// the same surfaces (the image does not change), the triangles of each leaf now far apart.
void scatter(scene::Scene& s, uint32_t quads) {
    std::vector<glm::vec3> places(s.vertices.size());
    for (size_t v = 0; v < places.size(); ++v) places[v] = s.vertices[v].position;
    uint32_t state = 12345u;
    for (uint32_t q = quads - 1; q > 0; --q) {
        state = state * 1664525u + 1013904223u;  // Numerical Recipes' LCG: a fixed order
        const uint32_t other = (state >> 8) % (q + 1);
        for (uint32_t k = 0; k < 4; ++k) std::swap(places[4 * q + k], places[4 * other + k]);
    }
    for (size_t v = 0; v < places.size(); ++v) s.vertices[v].position = places[v];
}

vplkit::RenderSettings direct_only() {
    vplkit::RenderSettings settings;
    settings.width = 64;
    settings.height = 64;
    return settings;
}

double max_difference(const std::vector<float>& a, const std::vector<float>& b) {
    double d = 0.0;
    for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::fabs(double(a[i]) - b[i]));
    return d;
}

}  // namespace

TEST_CASE("pose bvh: refitted while a motion keeps its cost, rebuilt when the motion scatters its leaves") {
    vplkit::Context& ctx = vplkit::test::context();
    constexpr uint32_t kGrid = 32;
    scene::Scene s = grid_scene(kGrid);
    vplkit::Renderer renderer(ctx, s);
    scene::Camera camera = scene::look_at({0.0f, -2.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, 0.9f);
    camera.znear = 0.01f;
    const auto still = renderer.render(camera, direct_only());

    // The first move builds on the GPU; a rigid translation then only refits, at the same cost.
    translate(s, {0.05f, 0.0f, 0.0f});
    const vplkit::PoseUpdate first = renderer.update_pose({true, false, false});
    CHECK(first.bvh == vplkit::BvhUpdate::rebuild);
    translate(s, {0.05f, 0.0f, 0.0f});
    const vplkit::PoseUpdate rigid = renderer.update_pose({true, false, false});
    CHECK(rigid.bvh == vplkit::BvhUpdate::refit);
    CHECK(rigid.bvh_cost_ratio == doctest::Approx(1.0).epsilon(1e-3));

    // Scattering the quads over the grid: the refitted boxes span the scene.
    scatter(s, kGrid * kGrid);
    const vplkit::PoseUpdate scattered = renderer.update_pose({true, false, false});
    CAPTURE(scattered.summary);
    CHECK(scattered.bvh == vplkit::BvhUpdate::rebuild);
    CHECK(scattered.refit_cost_ratio > vplkit::kBvhRebuildCostRatio);
    CHECK(scattered.bvh_cost_ratio == 1.0);
    CHECK(scattered.summary.find("BVH rebuilt on the GPU") != std::string::npos);

    // The frame through the rebuilt tree is the frame of a renderer made on the moved scene.
    const auto posed = renderer.render(camera, direct_only());
    vplkit::Renderer fresh(ctx, s);
    const auto expected = fresh.render(camera, direct_only());
    double peak = 0.0;
    for (float v : expected.direct) peak = std::max(peak, double(v));
    CHECK(max_difference(still.direct, expected.direct) > 0.01 * peak);  // the translation shows
    CHECK(max_difference(posed.direct, expected.direct) <= 1e-5 * peak);
}

TEST_CASE("pose bvh: a refit from the scene's vertex buffer (bvh_refit_gather) equals the refit from host vertices") {
    // The GPU pose's path: the moved vertices already in GpuScene's buffer, gathered on the GPU.
    vplkit::Context& ctx = vplkit::test::context();
    scene::Scene s = grid_scene(8);
    vplkit::GpuScene gpu = vplkit::GpuScene::create(ctx, s);
    vplkit::GpuBvhBuild from_host(ctx, scene::triangle_positions(s)), from_device(ctx, scene::triangle_positions(s));

    // A device pose's bookkeeping: the first one fills the second buffer with the current pose.
    vplkit::PassList start("device pose");
    const vplkit::BufferView posed = gpu.begin_device_pose(start);
    start.run(ctx);
    CHECK(gpu.has_motion());
    CHECK(posed.buffer == vplkit::BufferView(gpu.vertices()).buffer);
    const auto copied = gpu.vertices().download<scene::Vertex>(s.vertices.size());
    CHECK(std::equal(copied.begin(), copied.end(), s.vertices.begin(),
                     [](const scene::Vertex& a, const scene::Vertex& b) { return a.position == b.position; }));

    translate(s, {0.1f, -0.05f, 0.02f});
    scatter(s, 16);
    gpu.update_vertices(s);  // a second pose before a frame: into the same buffer, as a pose pass writes it
    from_host.refit(scene::triangle_positions(s));
    vplkit::PassList refit("device refit");
    from_device.add_refit_passes(refit, gpu.vertices(), gpu.indices());
    refit.run(ctx);
    from_device.finish_refit(refit.total_gpu_ms());

    const vplkit::GpuBvh& a = from_host.bvh();
    const vplkit::GpuBvh& b = from_device.bvh();
    REQUIRE(a.node_count == b.node_count);
    CHECK(a.scene_scale == b.scene_scale);
    const auto nodes_a = a.nodes.download<vplkit::shaders::BvhNode>(a.node_count);
    const auto nodes_b = b.nodes.download<vplkit::shaders::BvhNode>(b.node_count);
    CHECK(std::memcmp(nodes_a.data(), nodes_b.data(), nodes_a.size() * sizeof(nodes_a[0])) == 0);
    const auto tris_a = a.triangles.download<vplkit::shaders::BvhTriangle>(a.triangle_count);
    const auto tris_b = b.triangles.download<vplkit::shaders::BvhTriangle>(b.triangle_count);
    const auto same_triangle = [](const vplkit::shaders::BvhTriangle& x, const vplkit::shaders::BvhTriangle& y) {
        const auto same = [](const vplkit::shaders::vec3& p, const vplkit::shaders::vec3& q) {
            return p.x == q.x && p.y == q.y && p.z == q.z;
        };
        return same(x.v0, y.v0) && same(x.v1, y.v1) && same(x.v2, y.v2) && x.id == y.id && x.alpha == y.alpha;
    };
    CHECK(std::equal(tris_a.begin(), tris_a.end(), tris_b.begin(), same_triangle));  // padding aside
    // bvh_refit_gather against the CPU: each record's corners are its scene triangle's posed positions.
    const std::vector<glm::vec3> corners = scene::triangle_positions(s);
    const auto at = [](const vplkit::shaders::vec3& p) { return glm::vec3(p.x, p.y, p.z); };
    size_t gathered = 0;
    for (const vplkit::shaders::BvhTriangle& t : tris_b) {
        REQUIRE(3 * size_t(t.id) + 2 < corners.size());
        gathered +=
            at(t.v0) == corners[3 * t.id] && at(t.v1) == corners[3 * t.id + 1] && at(t.v2) == corners[3 * t.id + 2];
    }
    CHECK(!tris_b.empty());
    CHECK(gathered == tris_b.size());
    // The move shows in the root box.
    CHECK(nodes_b.at(0).lo.x > -1.0f + 0.05f);
}

TEST_CASE("pose bvh: the SAH cost of a BVH's nodes") {
    // The unit cube over two leaves (1 x 0.5 x 1 boxes) of 2 and 1 triangles: the root's visit,
    // then each leaf's triangles weighted by its half area over the root's.
    vplkit::shaders::BvhNode root{}, left{}, right{};
    root.lo = {0, 0, 0};
    root.hi = {1, 1, 1};
    left.lo = {0, 0, 0};
    left.hi = {1, 0.5f, 1};
    left.meta = vplkit::kBvhLeafFlag | 2u;
    right.lo = {0, 0.5f, 0};
    right.hi = {1, 1, 1};
    right.meta = vplkit::kBvhLeafFlag | 1u;
    const std::vector<vplkit::shaders::BvhNode> nodes = {root, left, right};
    // Half areas: root 3, each leaf 0.5 + 0.5 + 1 = 2.
    CHECK(vplkit::bvh_sah_cost(nodes) == doctest::Approx(1.0 + (2.0 * 2 + 2.0 * 1) / 3.0));
    CHECK(vplkit::bvh_sah_cost({}) == 0.0);
}
