// Node transforms on a hand-written file: a parent (translate, rotate 90 degrees about Z, scale 2)
// with a child (translate, non-uniform scale), a mesh instanced by two nodes (one through a
// mirroring matrix), a camera and lights placed by nodes. Every expected value below is worked
// out by hand in the comments.
//
// Tolerance 1e-5 on positions (float data through a double transform, rounded once) and 1e-5
// on unit vectors (normalized in double, rounded once).

#include "gltf_builder.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <cmath>

using namespace vplkit::scene;
using namespace scene_test;

namespace {

constexpr float kTolerance = 1e-5f;
const double kHalfSqrt2 = std::sqrt(0.5);

bool near(glm::vec3 a, glm::vec3 b) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(kTolerance)));
}

// Node layout (roots A, C, D, G; A's children B and E):
//   A: T(1,2,3) R_z(90) S(2)                 mesh 0 (triangle (0,0,0) (1,0,0) (0,1,0), normal +z)
//   B: A * T(1,0,0) S(1,3,1)                 mesh 1 (triangle (1,0,0) (0,1,0) (0,0,1), normal (1,1,1)/sqrt3)
//   E: A * T(0,0,1) R_x(-90)                 spot light
//   C: matrix T(0,0,5) S(-1,1,1)              mesh 0 again (mirrored)
//   D: T(0,0,10) R_y(90) S(2)                camera
//   G: T(3,3,3)                              point light
fs::path write_hierarchy(const fs::path& dir) {
    GltfBuilder b;
    const int p0 = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int n0 = b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int i0 = b.indices({0, 1, 2});
    b.mesh("[" + primitive(p0, n0, -1, -1, i0) + "]", "flat");
    const float s3 = float(1.0 / std::sqrt(3.0));
    const int p1 = b.vec3s({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
    const int n1 = b.vec3s({{s3, s3, s3}, {s3, s3, s3}, {s3, s3, s3}});
    b.mesh("[" + primitive(p1, n1) + "]", "slanted");  // not indexed
    const std::string h = json_float(kHalfSqrt2);
    b.node(R"({"name":"A","mesh":0,"translation":[1,2,3],"rotation":[0,0,)" + h + "," + h +
           R"(],"scale":[2,2,2],"children":[1,2]})");                          // 0
    b.node(R"({"name":"B","mesh":1,"translation":[1,0,0],"scale":[1,3,1]})");  // 1
    b.node(R"({"name":"E","translation":[0,0,1],"rotation":[-)" + h + ",0,0," + h +
           R"(],"extensions":{"KHR_lights_punctual":{"light":0}}})");                   // 2
    b.node(R"({"name":"C","mesh":0,"matrix":[-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1]})");  // 3
    b.node(R"({"name":"D","camera":0,"translation":[0,0,10],"rotation":[0,)" + h + ",0," + h +
           R"(],"scale":[2,2,2]})");                                                                   // 4
    b.node(R"({"name":"G","translation":[3,3,3],"extensions":{"KHR_lights_punctual":{"light":1}}})");  // 5
    b.roots = {0, 3, 4, 5};
    b.cameras.push_back(R"({"name":"side","type":"perspective","perspective":{"yfov":0.5,"znear":0.1}})");
    b.lights.push_back(R"({"name":"spot","type":"spot","color":[1,0.5,0.25],"intensity":3,"range":7,)"
                       R"("spot":{"innerConeAngle":0.2,"outerConeAngle":0.6}})");
    b.lights.push_back(R"({"name":"bulb","type":"point","intensity":2})");
    b.extensions_used = {"KHR_lights_punctual"};
    return b.write(dir, "hierarchy");
}

glm::vec3 position(const Scene& s, uint32_t triangle, int corner) {
    return s.vertices[s.indices[3 * triangle + corner]].position;
}

}  // namespace

TEST_CASE("parent and child transforms give hand-computed world positions") {
    TempDir dir("transforms");
    const Scene s = load_gltf(write_hierarchy(dir.path()));
    // Pre-order: A (mesh 0), B (mesh 1), C (mesh 0): mesh 0 appears once per node using it.
    REQUIRE(s.triangle_count() == 3);
    REQUIRE(s.primitives.size() == 3);
    CHECK(s.primitives[0].node == 0);
    CHECK(s.primitives[1].node == 1);
    CHECK(s.primitives[2].node == 3);
    CHECK(s.primitives[0].mesh == 0);
    CHECK(s.primitives[2].mesh == 0);

    // A: p -> T(1,2,3) + R_z90(2p), R_z90 (x,y,z) = (-y,x,z).
    //   (0,0,0) -> (1,2,3); (1,0,0) -> (0,2,0) + T = (1,4,3); (0,1,0) -> (-2,0,0) + T = (-1,2,3).
    CHECK(near(position(s, 0, 0), {1, 2, 3}));
    CHECK(near(position(s, 0, 1), {1, 4, 3}));
    CHECK(near(position(s, 0, 2), {-1, 2, 3}));
    // B: p -> M_A(T(1,0,0) + S(1,3,1) p).
    //   (1,0,0) -> (2,0,0) -> S2 (4,0,0) -> R (0,4,0) -> (1,6,3)
    //   (0,1,0) -> (1,3,0) -> (2,6,0) -> (-6,2,0) -> (-5,4,3)
    //   (0,0,1) -> (1,0,1) -> (2,0,2) -> (0,2,2) -> (1,4,5)
    CHECK(near(position(s, 1, 0), {1, 6, 3}));
    CHECK(near(position(s, 1, 1), {-5, 4, 3}));
    CHECK(near(position(s, 1, 2), {1, 4, 5}));
    // C mirrors x and moves to z = 5: (0,0,5), (-1,0,5), (0,1,5), stored with two corners swapped.
    CHECK(near(position(s, 2, 0), {0, 0, 5}));
    CHECK(near(position(s, 2, 1), {0, 1, 5}));
    CHECK(near(position(s, 2, 2), {-1, 0, 5}));
    CHECK(!s.primitives[0].mirrored);
    CHECK(!s.primitives[1].mirrored);
    CHECK(s.primitives[2].mirrored);
    CHECK(near(s.bounds.min, {-5, 0, 3}));
    CHECK(near(s.bounds.max, {1, 6, 5}));
}

TEST_CASE("normals use the inverse transpose and mirrored instances keep counter-clockwise fronts") {
    TempDir dir("normals");
    const Scene s = load_gltf(write_hierarchy(dir.path()));
    REQUIRE(s.triangle_count() == 3);
    // B's normal (1,1,1) under S(1,3,1): inverse transpose S(1,1/3,1) gives (1,1/3,1); then the
    // parent's rotation R_z90 gives (-1/3,1,1) (uniform scale 2 only changes length).
    const glm::vec3 expected = glm::normalize(glm::vec3(-1.0f / 3.0f, 1.0f, 1.0f));
    for (int k = 0; k < 3; ++k) CHECK(near(s.vertices[s.indices[3 + k]].normal, expected));
    // It is orthogonal to B's world triangle, whose edges are (-6,-2,0) and (0,-2,2).
    CHECK(std::abs(glm::dot(expected, glm::vec3(-6, -2, 0))) < kTolerance);
    CHECK(std::abs(glm::dot(expected, glm::vec3(0, -2, 2))) < kTolerance);
    // The mirror S(-1,1,1) maps the normal +z to +z (its inverse transpose is itself).
    for (int k = 0; k < 3; ++k) CHECK(near(s.vertices[s.indices[6 + k]].normal, {0, 0, 1}));
    // Every triangle's counter-clockwise geometric normal agrees with its vertex normals: for C
    // only because the winding was reversed ((-1,0,5) x ... would otherwise face -z).
    for (uint32_t t = 0; t < 3; ++t) {
        const glm::vec3 face = glm::cross(position(s, t, 1) - position(s, t, 0), position(s, t, 2) - position(s, t, 0));
        for (int k = 0; k < 3; ++k) CHECK(glm::dot(face, s.vertices[s.indices[3 * t + k]].normal) > 0.0f);
    }
}

TEST_CASE("cameras and lights take position and direction from their node") {
    TempDir dir("camera_lights");
    const Scene s = load_gltf(write_hierarchy(dir.path()));
    REQUIRE(s.cameras.size() == 1);
    const Camera& camera = s.cameras[0];
    CHECK(camera.name == "side");
    CHECK(camera.origin == CameraOrigin::file);
    // D: R_y90 maps -z to (-1,0,0); its scale 2 does not scale the camera.
    CHECK(near(camera.position, {0, 0, 10}));
    CHECK(near(camera.forward, {-1, 0, 0}));
    CHECK(near(camera.up, {0, 1, 0}));
    CHECK(camera.yfov == 0.5f);
    CHECK(camera.aspect == 0.0f);  // not given: the image's
    CHECK(camera.znear == doctest::Approx(0.1));
    CHECK(camera.zfar == 0.0f);  // not given: infinite
    // world_from_camera maps the camera's -z to forward, and view() is its inverse.
    const glm::mat4 world = camera.world_from_camera();
    CHECK(near(glm::vec3(world * glm::vec4(0, 0, -1, 0)), camera.forward));
    CHECK(near(glm::vec3(camera.view() * world * glm::vec4(1, 2, 3, 1)), {1, 2, 3}));

    REQUIRE(s.lights.size() == 2);  // pre-order: E (child of A) before G
    const Light& spot = s.lights[0];
    CHECK(spot.type == LightType::spot);
    CHECK(spot.name == "spot");
    // E: M_A (0,0,1) = R_z90 (0,0,2) + (1,2,3) = (1,2,5). Direction: R_x(-90) maps -z to -y, and
    // R_z90 maps -y to (1,0,0).
    CHECK(near(spot.position, {1, 2, 5}));
    CHECK(near(spot.direction, {1, 0, 0}));
    CHECK(near(spot.color, {1, 0.5f, 0.25f}));
    CHECK(spot.intensity == 3.0f);
    CHECK(spot.range == 7.0f);
    CHECK(spot.inner_cone_angle == doctest::Approx(0.2));
    CHECK(spot.outer_cone_angle == doctest::Approx(0.6));
    const Light& bulb = s.lights[1];
    CHECK(bulb.type == LightType::point);
    CHECK(near(bulb.position, {3, 3, 3}));
    CHECK(near(bulb.color, {1, 1, 1}));  // KHR_lights_punctual default colour
    CHECK(bulb.intensity == 2.0f);
}

TEST_CASE("asking for a camera makes it active") {
    TempDir dir("active_camera");
    const fs::path file = write_hierarchy(dir.path());
    LoadOptions options;
    options.camera = 0;
    const Scene s = load_gltf(file, options);
    CHECK(s.active_camera == 0);
    CHECK(s.camera().name == "side");
}
