// Animation playback (glTF 2.0 3.11, Appendix C): the loaded scene posed at a time, each
// interpolation against values worked out here independently of the loader: LINEAR and STEP by
// hand, CUBICSPLINE in Bezier form (control points p0, p0 + m0/3, p1 - m1/3, p1: the same curve
// as the spec's Hermite basis, computed another way), rotations as angles about one axis.
// Tolerance 1e-5 on positions of order 1 (float vertices, float keys).

#include "animation_files.hpp"
#include "feature_files.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace {

using gltf_features::AnimationKeys;
using gltf_features::ChannelKeys;
using vplkit::scene::Scene;

constexpr float kTolerance = 1e-5f;
const std::vector<glm::vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};

Scene load_at(const scene_test::GltfBuilder& b, double t, const std::string& name = "animated") {
    scene_test::TempDir dir(name);
    vplkit::scene::LoadOptions options;
    options.time = t;
    return vplkit::scene::load_gltf(b.write(dir.path(), name, true), options);
}

void check_positions(const Scene& scene, const std::vector<glm::vec3>& expected) {
    REQUIRE(scene.vertices.size() == expected.size());
    for (size_t v = 0; v < expected.size(); ++v) {
        CAPTURE(v);
        CAPTURE(scene.vertices[v].position.x);
        CAPTURE(scene.vertices[v].position.y);
        CAPTURE(scene.vertices[v].position.z);
        CHECK(glm::length(scene.vertices[v].position - expected[v]) <= kTolerance);
    }
}

// The quad's corners moved by `offset`.
std::vector<glm::vec3> moved_quad(glm::vec3 offset) {
    std::vector<glm::vec3> out;
    for (const glm::vec3& corner : kQuad) out.push_back(corner + offset);
    return out;
}

// The cubic with end values p0, p1 and end slopes m0, m1 (per unit s) at s, from its Bezier control points.
double bezier(double p0, double m0, double p1, double m1, double s) {
    const double c1 = p0 + m0 / 3.0, c2 = p1 - m1 / 3.0, r = 1.0 - s;
    return r * r * r * p0 + 3.0 * r * r * s * c1 + 3.0 * r * s * s * c2 + s * s * s * p1;
}

// (x, y, z, w) of a rotation by `degrees` about +Z.
std::vector<float> z_rotation(double degrees) {
    const double half = degrees * std::numbers::pi / 360.0;
    return {0.0f, 0.0f, float(std::sin(half)), float(std::cos(half))};
}

// The quad rotated by `degrees` about +Z through the origin.
std::vector<glm::vec3> turned_quad(double degrees) {
    const double a = degrees * std::numbers::pi / 180.0;
    std::vector<glm::vec3> out;
    for (const glm::vec3& p : kQuad) {
        out.push_back(glm::vec3(float(p.x * std::cos(a) - p.y * std::sin(a)),
                                float(p.x * std::sin(a) + p.y * std::cos(a)), 0.0f));
    }
    return out;
}

std::vector<float> concat(std::vector<float> a, const std::vector<float>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

}  // namespace

TEST_CASE("gltf animation: LINEAR translation and scale at and between keys, clamped outside them") {
    // Keys at 0, 1, 3 s: (0,0,0), (2,0,0), (2,4,0).
    const ChannelKeys move{0, "translation", "LINEAR", {0, 1, 3}, {0, 0, 0, 2, 0, 0, 2, 4, 0}};
    const auto b = gltf_features::animated_quad({{"move", {move}}});
    const std::vector<std::pair<double, glm::vec3>> expected = {{-1.0, {0, 0, 0}}, {0.0, {0, 0, 0}}, {0.5, {1, 0, 0}},
                                                                {1.0, {2, 0, 0}},  {2.0, {2, 2, 0}}, {2.5, {2, 3, 0}},
                                                                {3.0, {2, 4, 0}},  {5.0, {2, 4, 0}}};
    for (const auto& [t, offset] : expected) {
        CAPTURE(t);
        const Scene scene = load_at(b, t);
        check_positions(scene, moved_quad(offset));
        CHECK(vplkit::scene::warning_lines(scene.warnings).empty());
        REQUIRE(scene.time);
        CHECK(*scene.time == t);
    }
    // Scale (1,1,1) -> (3,1,1) over 0..1 s: at 0.5 s x doubles.
    const ChannelKeys grow{0, "scale", "LINEAR", {0, 1}, {1, 1, 1, 3, 1, 1}};
    check_positions(load_at(gltf_features::animated_quad({{"grow", {grow}}}), 0.5),
                    {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}});
}

TEST_CASE("gltf animation: STEP holds each key's value until the next key") {
    const ChannelKeys move{0, "translation", "STEP", {0, 1, 3}, {0, 0, 0, 2, 0, 0, 2, 4, 0}};
    const auto b = gltf_features::animated_quad({{"", {move}}});
    const std::vector<std::pair<double, glm::vec3>> expected = {
        {-1.0, {0, 0, 0}}, {0.999, {0, 0, 0}}, {1.0, {2, 0, 0}}, {2.5, {2, 0, 0}}, {3.0, {2, 4, 0}}, {10.0, {2, 4, 0}}};
    for (const auto& [t, offset] : expected) {
        CAPTURE(t);
        check_positions(load_at(b, t), moved_quad(offset));
    }
}

TEST_CASE("gltf animation: CUBICSPLINE follows the Hermite curve, tangents scaled by the key interval") {
    // Keys at 1, 3, 4 s; per key in-tangent, value, out-tangent. Key 0's in-tangent and the last
    // key's out-tangent are never used (9s).
    const std::vector<glm::vec3> in = {{9, 9, 9}, {0, 2, 1}, {0, 1, 0}};
    const std::vector<glm::vec3> value = {{0, 0, 0}, {2, 1, 0}, {2, 3, 0}};
    const std::vector<glm::vec3> out = {{1, 0, -1}, {1, 1, 1}, {9, 9, 9}};
    const std::vector<double> times = {1, 3, 4};
    ChannelKeys curve{0, "translation", "CUBICSPLINE", {1, 3, 4}, {}};
    for (size_t k = 0; k < 3; ++k) {
        for (const glm::vec3& v : {in[k], value[k], out[k]}) curve.values.insert(curve.values.end(), {v.x, v.y, v.z});
    }
    const auto b = gltf_features::animated_quad({{"curve", {curve}}});
    for (double t : {0.5, 1.0, 1.5, 2.0, 2.9, 3.0, 3.25, 3.75, 4.0, 4.5}) {
        CAPTURE(t);
        glm::vec3 expected;
        if (t <= times.front()) {
            expected = value.front();
        } else if (t >= times.back()) {
            expected = value.back();
        } else {
            const size_t k = t < times[1] ? 0 : 1;
            const double dt = times[k + 1] - times[k], s = (t - times[k]) / dt;
            for (int c = 0; c < 3; ++c) {
                expected[c] = float(bezier(value[k][c], dt * out[k][c], value[k + 1][c], dt * in[k + 1][c], s));
            }
        }
        check_positions(load_at(b, t), moved_quad(expected));
    }
}

TEST_CASE("gltf animation: LINEAR rotations slerp along the shorter arc, normalized integer keys too") {
    // 0 -> 120 degrees about +Z over 0..1 s: a spherical interpolation turns at a constant rate
    // (a normalized lerp would give 27.8 degrees at 0.25 s instead of 30).
    for (bool negated : {false, true}) {
        CAPTURE(negated);
        std::vector<float> end = z_rotation(120.0);
        if (negated) {
            for (float& v : end) v = -v;  // the same rotation: slerp must take the shorter arc
        }
        const ChannelKeys turn{0, "rotation", "LINEAR", {0, 1}, concat(z_rotation(0.0), end)};
        const auto b = gltf_features::animated_quad({{"turn", {turn}}});
        for (double t : {0.25, 0.5, 1.0}) {
            CAPTURE(t);
            check_positions(load_at(b, t), turned_quad(120.0 * t));
        }
    }
    // Identity -> 180 degrees about +Z, keys exact in every normalized integer type glTF allows.
    for (int type : {scene_test::kFloat, scene_test::kByte, scene_test::kUnsignedByte, scene_test::kShort,
                     scene_test::kUnsignedShort}) {
        CAPTURE(type);
        ChannelKeys turn{0, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0, 1, 0}};
        turn.component_type = type;
        const auto b = gltf_features::animated_quad({{"turn", {turn}}});
        check_positions(load_at(b, 0.25), turned_quad(45.0));
        check_positions(load_at(b, 0.5), turned_quad(90.0));
    }
    // CUBICSPLINE rotations are normalized: zero tangents, identity -> 180 degrees, half-way is
    // (0, 0, 0.5, 0.5) before normalization: 90 degrees.
    const std::vector<float> zero = {0, 0, 0, 0};
    ChannelKeys cubic{0, "rotation", "CUBICSPLINE", {0, 2}, {}};
    cubic.values = concat(concat(concat(zero, {0, 0, 0, 1}), zero), concat(concat(zero, {0, 0, 1, 0}), zero));
    check_positions(load_at(gltf_features::animated_quad({{"cubic", {cubic}}}), 1.0), turned_quad(90.0));
}

TEST_CASE("gltf animation: morph weights move the morphed vertices (LINEAR, CUBICSPLINE, normalized bytes)") {
    // morph_quad: target 0 lifts vertices 1 and 2 by (0, 0, 2), target 1 moves all by (1, 0, 0).
    auto expected_for = [](double w0, double w1) {
        std::vector<glm::vec3> out;
        for (size_t v = 0; v < kQuad.size(); ++v) {
            const double lift = v == 1 || v == 2 ? 2.0 * w0 : 0.0;
            out.push_back(kQuad[v] + glm::vec3(float(w1), 0.0f, float(lift)));
        }
        return out;
    };
    {
        auto b = gltf_features::morph_quad();
        gltf_features::add_animations(b, {{"morph", {{0, "weights", "LINEAR", {0, 1}, {0, 0, 1, 0.5f}}}}});
        check_positions(load_at(b, 0.5), expected_for(0.5, 0.25));
        check_positions(load_at(b, 7.0), expected_for(1.0, 0.5));
    }
    {
        // Per key: in-tangents of both targets, their values, their out-tangents.
        auto b = gltf_features::morph_quad();
        gltf_features::add_animations(
            b, {{"morph", {{0, "weights", "CUBICSPLINE", {0, 2}, {0, 0, 0, 0, 1, -1, 0.5f, 0, 1, 0.5f, 0, 0}}}}});
        const double s = 0.5, dt = 2.0;
        check_positions(load_at(b, 1.0),
                        expected_for(bezier(0, dt * 1, 1, dt * 0.5, s), bezier(0, dt * -1, 0.5, dt * 0, s)));
    }
    {
        ChannelKeys bytes{0, "weights", "LINEAR", {0, 1}, {0, 0, 1, 1}};
        bytes.component_type = scene_test::kUnsignedByte;
        auto b = gltf_features::morph_quad();
        gltf_features::add_animations(b, {{"morph", {bytes}}});
        check_positions(load_at(b, 0.25), expected_for(0.25, 0.25));
    }
}

TEST_CASE("gltf animation: an animated joint moves the skinned vertices it carries") {
    // skinned_quad(0): node 0 "arm" (joint 1, at (0.5, 0, 0)), node 1 "hip" (joint 0, its parent).
    // The arm turns 0 -> 90 degrees about +Y and the hip rises 0 -> 2 over 0..1 s.
    auto b = gltf_features::skinned_quad(0.0f);
    const double q = std::sqrt(0.5);
    gltf_features::add_animations(b, {{"wave",
                                       {{0, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, float(q), 0, float(q)}},
                                        {1, "translation", "LINEAR", {0, 1}, {0, 0, 0, 0, 2, 0}}}}});
    for (double t : {0.0, 0.5, 1.0, 3.0}) {
        CAPTURE(t);
        const double a = std::min(t, 1.0) * std::numbers::pi / 2;
        const glm::vec3 hip(0.0f, float(2.0 * std::min(t, 1.0)), 0.0f);
        // Vertex 1 (1, 0, 0) follows the arm: its bind offset (0.5, 0, 0) turned, plus the arm's place.
        const glm::vec3 arm_vertex(float(0.5 + 0.5 * std::cos(a)), 0.0f, float(-0.5 * std::sin(a)));
        const glm::vec3 blended = 0.5f * glm::vec3(1, 1, 0) + 0.5f * (arm_vertex + glm::vec3(0, 1, 0));
        check_positions(load_at(b, t, "skin"),
                        {hip + glm::vec3(0, 0, 0), hip + arm_vertex, hip + blended, hip + glm::vec3(0, 1, 0)});
    }
}

TEST_CASE("gltf animation: lights and cameras on animated nodes move with them") {
    auto b = gltf_features::animated_quad({});
    b.cameras.push_back(R"({"type":"perspective","perspective":{"yfov":0.8,"znear":0.1,"zfar":10}})");
    b.roots.push_back(b.node(R"({"camera":0,"translation":[0,0,2]})"));
    b.lights.push_back(R"({"type":"spot","intensity":3,"spot":{"outerConeAngle":0.5}})");
    b.roots.push_back(b.node(R"({"translation":[0,2,0],"extensions":{"KHR_lights_punctual":{"light":1}}})"));
    const double q = std::sqrt(0.5);
    // Point light (node 1) slides +x; the camera (node 2) turns 90 degrees about +Y and rises;
    // the spot (node 3) turns from -Z to -Y (90 degrees about +X), STEP.
    gltf_features::add_animations(b, {{"lights",
                                       {{1, "translation", "LINEAR", {0, 2}, {0.5f, 0.5f, 1, 2.5f, 0.5f, 1}},
                                        {2, "rotation", "LINEAR", {0, 2}, {0, 0, 0, 1, 0, float(q), 0, float(q)}},
                                        {2, "translation", "LINEAR", {0, 2}, {0, 0, 2, 0, 4, 2}},
                                        {3, "rotation", "STEP", {0, 1}, {0, 0, 0, 1, -float(q), 0, 0, float(q)}}}}});
    const Scene half = load_at(b, 1.0, "lights");
    REQUIRE(half.lights.size() == 2);
    CHECK(glm::length(half.lights[0].position - glm::vec3(1.5f, 0.5f, 1.0f)) <= kTolerance);
    CHECK(glm::length(half.lights[1].direction - glm::vec3(0, -1, 0)) <= kTolerance);
    REQUIRE(half.cameras.size() == 1);
    const float h = std::sqrt(0.5f);
    CHECK(glm::length(half.camera().position - glm::vec3(0, 2, 2)) <= kTolerance);
    CHECK(glm::length(half.camera().forward - glm::vec3(-h, 0, -h)) <= kTolerance);
    const Scene start = load_at(b, 0.0, "lights");
    CHECK(glm::length(start.lights[0].position - glm::vec3(0.5f, 0.5f, 1.0f)) <= kTolerance);
    CHECK(glm::length(start.lights[1].direction - glm::vec3(0, 0, -1)) <= kTolerance);
    CHECK(glm::length(start.camera().forward - glm::vec3(0, 0, -1)) <= kTolerance);
}
