#include "skinned_tube.hpp"

#include "animation_files.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace gltf_features {

namespace {

constexpr float kHeight = 2.0f;
constexpr float kRadius = 0.3f;
constexpr double kPi = 3.14159265358979323846;

// (x, y, z, w) of a rotation by `degrees` about +Z.
std::vector<float> z_rotation(double degrees) {
    const double half = 0.5 * degrees * kPi / 180.0;
    return {0.0f, 0.0f, float(std::sin(half)), float(std::cos(half))};
}

std::string ints(std::initializer_list<int> values) {
    std::string out;
    for (int v : values) out += (out.empty() ? "" : ",") + std::to_string(v);
    return out;
}

}  // namespace

scene_test::GltfBuilder skinned_tube(uint32_t rings, uint32_t sides) {
    using scene_test::json_float;
    scene_test::GltfBuilder b;
    std::vector<glm::vec3> positions, normals, bulge, bulge_normals, bulge_tangents;
    std::vector<glm::vec4> tangents, weights;
    std::vector<uint16_t> joints;
    std::vector<uint32_t> indices;
    for (uint32_t r = 0; r < rings; ++r) {
        const float y = kHeight * float(r) / float(rings - 1);
        const float s = 2.0f * y / kHeight;  // 0, 1, 2 at the joints
        const uint16_t lower = uint16_t(std::min(int(s), 1));
        const float upper = s - float(lower);
        for (uint32_t k = 0; k <= sides; ++k) {
            const float a = float(2.0 * kPi * k / sides);
            const glm::vec3 radial(std::cos(a), 0.0f, std::sin(a));
            positions.push_back(glm::vec3(0.0f, y, 0.0f) + kRadius * radial);
            normals.push_back(radial);
            tangents.push_back({-std::sin(a), 0.0f, std::cos(a), r % 2 ? -1.0f : 1.0f});
            // Weights summing to 1.02: the pose rescales them to 1.
            joints.insert(joints.end(), {lower, uint16_t(lower + 1), 0, 2});
            weights.push_back({0.98f * (1.0f - upper), 0.98f * upper, 0.03f, 0.01f});
            const float bump = 0.1f * std::sin(float(kPi) * y / kHeight);
            bulge.push_back(bump * radial);
            bulge_normals.push_back({0.0f, -0.2f * std::cos(float(kPi) * y / kHeight), 0.0f});
            bulge_tangents.push_back({0.0f, 0.1f, 0.0f});
        }
    }
    const uint32_t columns = sides + 1;
    for (uint32_t r = 0; r + 1 < rings; ++r) {
        for (uint32_t k = 0; k < sides; ++k) {
            const uint32_t a = r * columns + k, c = a + columns;
            // (tangent, +Y, normal) is left-handed here: a, c, c + 1 runs counter-clockwise from outside.
            indices.insert(indices.end(), {a, c, c + 1, a, c + 1, a + 1});
        }
    }
    const int p = b.vec3s(positions), n = b.vec3s(normals), t = b.vec4s(tangents), w = b.vec4s(weights);
    const int j = b.accessor(b.view(joints.data(), joints.size() * sizeof(uint16_t)), scene_test::kUnsignedShort,
                             positions.size(), "VEC4");
    const int dp = b.vec3s(bulge), dn = b.vec3s(bulge_normals), dt = b.vec3s(bulge_tangents);
    const int i = b.indices(indices, scene_test::kUnsignedInt);
    const int tube = b.mesh("[{\"attributes\":{\"POSITION\":" + std::to_string(p) + ",\"NORMAL\":" + std::to_string(n) +
                            ",\"TANGENT\":" + std::to_string(t) + ",\"JOINTS_0\":" + std::to_string(j) +
                            ",\"WEIGHTS_0\":" + std::to_string(w) + "},\"indices\":" + std::to_string(i) +
                            ",\"targets\":[{\"POSITION\":" + std::to_string(dp) + ",\"NORMAL\":" + std::to_string(dn) +
                            ",\"TANGENT\":" + std::to_string(dt) + "}]}]");
    // Column-major inverse binds: the joints rest at heights 0, 1, 2 on the axis.
    std::vector<float> ibm;
    for (int k = 0; k < 3; ++k) ibm.insert(ibm.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -float(k), 0, 1});
    const int ibm_accessor = b.accessor(b.view(ibm.data(), ibm.size() * sizeof(float)), scene_test::kFloat, 3, "MAT4");

    const int joint2 = b.node(R"({"name":"joint 2","translation":[0,1,0]})");
    const int joint1 = b.node("{\"name\":\"joint 1\",\"translation\":[0,1,0],\"children\":[" + ints({joint2}) + "]}");
    const int joint0 = b.node("{\"name\":\"joint 0\",\"children\":[" + ints({joint1}) + "]}");
    const int body = b.node("{\"name\":\"tube\",\"mesh\":" + std::to_string(tube) + ",\"skin\":0}");
    const int qn = b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int qp = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int qt = b.vec4s({{1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}});
    const int qi = b.indices({0, 1, 2, 0, 2, 3});
    const int quad_mesh =
        b.mesh("[{\"attributes\":{\"POSITION\":" + std::to_string(qp) + ",\"NORMAL\":" + std::to_string(qn) +
               ",\"TANGENT\":" + std::to_string(qt) + "},\"indices\":" + std::to_string(qi) + "}]");
    const int quad = b.node("{\"name\":\"quad\",\"mesh\":" + std::to_string(quad_mesh) +
                            ",\"translation\":[1,0,-1],\"scale\":[-1,1,1]}");
    b.lights.push_back(R"({"type":"point","color":[1,1,1],"intensity":5})");
    const int light = b.node(R"({"translation":[0,1,2],"extensions":{"KHR_lights_punctual":{"light":0}}})");
    b.roots = {joint0, body, quad, light};
    b.top_level_extra = ",\"skins\":[{\"joints\":[" + ints({joint0, joint1, joint2}) +
                        "],\"inverseBindMatrices\":" + std::to_string(ibm_accessor) + "}]";

    std::vector<float> bend1, bend2, spin;
    for (double d : {0.0, 30.0, -20.0}) {
        const std::vector<float> q1 = z_rotation(d), q2 = z_rotation(-0.5 * d), q3 = z_rotation(3.0 * d);
        bend1.insert(bend1.end(), q1.begin(), q1.end());
        bend2.insert(bend2.end(), q2.begin(), q2.end());
        spin.insert(spin.end(), q3.begin(), q3.end());
    }
    const std::vector<float> times = {0.0f, 1.0f, 2.0f};
    add_animations(b, {{"bend",
                        {{joint1, "rotation", "LINEAR", times, bend1},
                         {joint2, "rotation", "LINEAR", times, bend2},
                         {joint0, "translation", "LINEAR", times, {0, 0, 0, 0.2f, 0, 0, -0.1f, 0.1f, 0}},
                         {body, "weights", "LINEAR", times, {0.0f, 1.0f, 0.5f}},
                         {quad, "rotation", "LINEAR", times, spin},
                         {quad, "translation", "STEP", times, {1, 0, -1, 1.5f, 0, -1, 1.5f, 0.5f, -1}}}}});
    (void)json_float;
    return b;
}

}  // namespace gltf_features
