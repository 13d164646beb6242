// The in-repo scenes (scenes/cornell_*) and the third-party ones in ../shared/scenes: counts,
// instancing, lights, cameras, emitters, and the invariants every loaded scene must satisfy.
//
// Tolerances: positions come from float data through a double-precision transform rounded to
// float once, so hand-computed values match to 1e-5 (a few ulp at unit scale); unit vectors are
// checked to 1e-4 (float normalization of transformed vectors).

#include "gltf_builder.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

using namespace vplkit::scene;
using scene_test::shared_scenes;
using scene_test::source_dir;

namespace {

constexpr float kPosition = 1e-5f;
constexpr float kUnit = 1e-4f;

bool near(glm::vec3 a, glm::vec3 b, float tolerance) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tolerance)));
}

// What must hold for any scene load_gltf returns.
void check_invariants(const Scene& s) {
    REQUIRE(s.indices.size() % 3 == 0);
    REQUIRE(s.triangle_materials.size() == s.triangle_count());
    REQUIRE(std::all_of(s.indices.begin(), s.indices.end(), [&](uint32_t i) { return i < s.vertices.size(); }));
    REQUIRE(std::all_of(s.triangle_materials.begin(), s.triangle_materials.end(),
                        [&](uint32_t m) { return m < s.materials.size(); }));
    size_t bad_normals = 0, bad_tangents = 0;
    for (const Vertex& v : s.vertices) {
        if (std::abs(glm::length(v.normal) - 1.0f) > kUnit) ++bad_normals;
        if (v.tangent.w != 0.0f) {
            if (std::abs(glm::length(glm::vec3(v.tangent)) - 1.0f) > kUnit ||
                std::abs(glm::dot(glm::vec3(v.tangent), v.normal)) > kUnit || std::abs(v.tangent.w) != 1.0f) {
                ++bad_tangents;
            }
        }
    }
    CHECK(bad_normals == 0);
    CHECK(bad_tangents == 0);
    // Every triangle lies inside the bounds, and the bounds are tight.
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (uint32_t i : s.indices) lo = glm::min(lo, s.vertices[i].position), hi = glm::max(hi, s.vertices[i].position);
    CHECK(lo == s.bounds.min);
    CHECK(hi == s.bounds.max);
    // The emissive list is exactly the triangles whose material emits.
    size_t emissive = 0;
    for (size_t t = 0; t < s.triangle_count(); ++t) emissive += s.materials[s.triangle_materials[t]].emits();
    CHECK(emissive == s.emissive_triangles.size());
    // Primitive instances tile the triangle array in order.
    uint32_t next = 0;
    size_t outside = 0, untangented = 0;
    for (const PrimitiveInstance& p : s.primitives) {
        CHECK(p.first_triangle == next);
        next += p.triangle_count;
        for (uint32_t t = p.first_triangle; t < p.first_triangle + p.triangle_count; ++t) {
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = s.indices[3 * t + k];
                outside += v < p.first_vertex || v >= p.first_vertex + p.vertex_count;
            }
        }
        untangented += s.materials[p.material].normal_texture != kNoTexture && p.tangents == TangentSource::none;
    }
    CHECK(next == s.triangle_count());
    CHECK(outside == 0);      // each instance's triangles use only its own vertices
    CHECK(untangented == 0);  // normal-textured primitives have tangents
    for (const Image& image : s.images) {
        CHECK(image.rgba.size() == size_t(image.width) * image.height * 4);
        CHECK((image.srgb || image.linear));
    }
    for (const Texture& texture : s.textures) CHECK(texture.image < s.images.size());
    REQUIRE(!s.cameras.empty());
    CHECK(s.active_camera < s.cameras.size());
}

// The triangles of one instance, by node name.
const PrimitiveInstance* instance_of_node(const Scene& s, uint32_t node) {
    for (const auto& p : s.primitives) {
        if (p.node == node) return &p;
    }
    return nullptr;
}

// Loads `path` and reports (not asserts: timing belongs to benchmarks) how long it took, for
// `ctest -R 'scene/shared' -V`.
Scene timed_load(const std::filesystem::path& path) {
    const auto start = std::chrono::steady_clock::now();
    Scene s = load_gltf(path);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    size_t pixels = 0;
    for (const Image& image : s.images) pixels += size_t(image.width) * image.height;
    MESSAGE(path.filename().string() << " loaded in " << seconds << " s: " << s.triangle_count() << " triangles, "
                                     << s.materials.size() << " materials, " << s.textures.size() << " textures, "
                                     << s.images.size() << " images (" << double(pixels) * 1e-6 << " Mpixel)");
    return s;
}

glm::vec3 centroid(const Scene& s, const PrimitiveInstance& p) {
    glm::dvec3 sum(0.0);
    for (uint32_t v = p.first_vertex; v < p.first_vertex + p.vertex_count; ++v)
        sum += glm::dvec3(s.vertices[v].position);
    return glm::vec3(sum / double(p.vertex_count));
}

}  // namespace

TEST_CASE("in-repo cornell_point: counts and instanced blocks and light and camera") {
    const Scene s = load_gltf(source_dir() + "/scenes/cornell_point/cornell_point.gltf");
    check_invariants(s);
    CHECK(s.triangle_count() == 34);  // 5 walls x 2 + 2 blocks x 12
    CHECK(s.vertices.size() == 68);
    CHECK(s.materials.size() == 3);
    CHECK(s.primitives.size() == 7);
    CHECK(s.emissive_triangles.empty());
    CHECK(s.warnings.degenerate_triangles == 0);
    CHECK(s.warnings.messages.empty());
    CHECK(s.bounds.min == glm::vec3(-1, 0, -1));
    CHECK(s.bounds.max == glm::vec3(1, 2, 1));

    // Nodes 6 and 7 both instance mesh 5 (the unit cube) under parent node 5 (translation 0.3 up).
    const PrimitiveInstance* short_block = instance_of_node(s, 6);
    const PrimitiveInstance* tall_block = instance_of_node(s, 7);
    REQUIRE(short_block);
    REQUIRE(tall_block);
    CHECK(short_block->mesh == 5);
    CHECK(tall_block->mesh == 5);
    CHECK(short_block->triangle_count == 12);
    CHECK(tall_block->triangle_count == 12);
    CHECK(near(centroid(s, *short_block), {0.35f, 0.3f, 0.3f}, kPosition));
    CHECK(near(centroid(s, *tall_block), {-0.35f, 0.6f, -0.3f}, kPosition));
    float short_top = -1, tall_top = -1, bottom = 1;
    for (uint32_t v = 0; v < 24; ++v) {
        short_top = std::max(short_top, s.vertices[short_block->first_vertex + v].position.y);
        tall_top = std::max(tall_top, s.vertices[tall_block->first_vertex + v].position.y);
        bottom = std::min({bottom, s.vertices[short_block->first_vertex + v].position.y,
                           s.vertices[tall_block->first_vertex + v].position.y});
    }
    CHECK(short_top == doctest::Approx(0.6).epsilon(1e-6));
    CHECK(tall_top == doctest::Approx(1.2).epsilon(1e-6));
    CHECK(std::abs(bottom) < kPosition);  // both blocks stand on the floor

    REQUIRE(s.lights.size() == 1);
    const Light& light = s.lights[0];
    CHECK(light.type == LightType::point);
    CHECK(light.origin == LightOrigin::file);
    CHECK(light.name == "ceiling_point");
    CHECK(near(light.position, {0, 1.9f, 0}, kPosition));
    CHECK(near(light.color, {1, 0.85f, 0.6f}, 1e-7f));
    CHECK(light.intensity == 8.0f);
    CHECK(light.range == 0.0f);

    REQUIRE(s.cameras.size() == 1);
    const Camera& camera = s.camera();
    CHECK(camera.origin == CameraOrigin::file);
    CHECK(camera.name == "front");
    CHECK(near(camera.position, {0, 1, 3.4f}, kPosition));
    CHECK(near(camera.forward, {0, 0, -1}, kUnit));
    CHECK(near(camera.up, {0, 1, 0}, kUnit));
    CHECK(camera.yfov == doctest::Approx(glm::radians(45.0)).epsilon(1e-6));
    CHECK(camera.aspect == 1.0f);
    CHECK(camera.znear == doctest::Approx(0.05));
    CHECK(camera.zfar == doctest::Approx(20.0));
}

TEST_CASE("in-repo cornell_emissive: the emissive quad is the emissive triangle list") {
    const Scene s = load_gltf(source_dir() + "/scenes/cornell_emissive/cornell_emissive.gltf");
    check_invariants(s);
    CHECK(s.triangle_count() == 36);
    CHECK(s.materials.size() == 4);
    CHECK(s.lights.empty());
    REQUIRE(s.emissive_triangles.size() == 2);
    for (uint32_t t : s.emissive_triangles) {
        const Material& m = s.materials[s.triangle_materials[t]];
        CHECK(m.name == "ceiling_light");
        CHECK(m.emissive_strength == 40.0f);
        CHECK(near(m.emission(), {40.0f, 34.0f, 24.0f}, 1e-4f));
        for (int k = 0; k < 3; ++k) {
            const Vertex& v = s.vertices[s.indices[3 * t + k]];
            CHECK(v.position.y == doctest::Approx(1.99));
            CHECK(near(v.normal, {0, -1, 0}, kUnit));
        }
    }
}

TEST_CASE("shared CornellBox: 32 triangles and an emissive quad and a generated camera") {
    const auto path = shared_scenes() / "CornellBox" / "CornellBox.gltf";
    if (!std::filesystem::exists(path)) {
        MESSAGE("skipped: " << path.string() << " not found (../shared/scenes is not beside the repository)");
        return;
    }
    const Scene s = load_gltf(path);
    check_invariants(s);
    CHECK(s.triangle_count() == 32);
    CHECK(s.materials.size() == 8);
    CHECK(s.lights.empty());
    REQUIRE(s.emissive_triangles.size() == 2);
    // PROVENANCE.md: Ke (17, 12, 4) -> emissiveFactor (1, 12/17, 4/17), strength 17.
    CHECK(near(s.materials[s.triangle_materials[s.emissive_triangles[0]]].emission(), {17, 12, 4}, 1e-4f));
    REQUIRE(s.cameras.size() == 1);
    const Camera& camera = s.camera();
    CHECK(camera.origin == CameraOrigin::generated);
    // The generated camera sees the whole bounding sphere: centre straight ahead, radius within
    // half the field of view.
    const glm::vec3 to_center = s.bounds.center() - camera.position;
    CHECK(near(glm::normalize(to_center), camera.forward, kUnit));
    const float radius = 0.5f * glm::length(s.bounds.extent());
    CHECK(std::asin(radius / glm::length(to_center)) <= camera.yfov * 0.5f + 1e-5f);
    CHECK(camera.znear > 0.0f);
    CHECK(camera.zfar > glm::length(to_center) + radius);
}

TEST_CASE("shared Sponza: counts and textures and generated tangents") {
    const auto path = shared_scenes() / "Sponza" / "Sponza.gltf";
    if (!std::filesystem::exists(path)) {
        MESSAGE("skipped: " << path.string() << " not found");
        return;
    }
    const Scene s = timed_load(path);
    check_invariants(s);
    CHECK(s.triangle_count() == 262087);
    CHECK(s.materials.size() == 24);
    CHECK(s.textures.size() == 49);
    CHECK(s.images.size() == 49);
    CHECK(s.primitives.size() == 170);  // PROVENANCE.md: 170 mesh nodes
    CHECK(s.cameras.size() == 4);
    CHECK(s.cameras[0].name == "CameraMain");
    CHECK(s.lights.empty());
    CHECK(s.emissive_triangles.empty());
    size_t srgb = 0, linear = 0, generated = 0;
    for (const Image& image : s.images) srgb += image.srgb, linear += image.linear;
    for (const PrimitiveInstance& p : s.primitives) generated += p.tangents == TangentSource::generated;
    CHECK(srgb > 0);
    CHECK(linear > 0);
    CHECK(srgb + linear == s.images.size());  // no image is both colour and data here
    CHECK(generated > 0);                     // normal-mapped primitives have no TANGENT (PROVENANCE.md)
}

TEST_CASE("shared BreakfastRoom: counts and the ignored extension") {
    const auto path = shared_scenes() / "BreakfastRoom" / "BreakfastRoom.gltf";
    if (!std::filesystem::exists(path)) {
        MESSAGE("skipped: " << path.string() << " not found");
        return;
    }
    const Scene s = timed_load(path);
    check_invariants(s);
    CHECK(s.triangle_count() == 262685);
    CHECK(s.materials.size() == 14);
    CHECK(s.textures.size() == 3);
    CHECK(s.images.size() == 3);
    CHECK(s.cameras.size() == 3);
    CHECK(s.warnings.degenerate_triangles == 2);
    const auto& messages = s.warnings.messages;
    CHECK(std::any_of(messages.begin(), messages.end(),
                      [](const std::string& m) { return m.find("KHR_materials_specular") != std::string::npos; }));
}
