// KHR_mesh_quantization: integer positions (normalized unsigned short; unnormalized short
// dequantized by the node's scale), normalized byte normals and unsigned byte UVs load as the
// float quad and render where it renders.
//
// Expectation: the float unit quad (scene_test::unit_quad). Tolerances: loader 1e-6 (0 and 1 are
// exact in every encoding; the node scale 0.001 x 1000 rounds to 1 in float); G-buffer: identical
// coverage and positions within 1e-6 (the same triangles under the same generated camera).

#include "feature_files.hpp"
#include "gbuffer_readback.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

namespace {

vplkit::scene::Scene load(const scene_test::GltfBuilder& b, const std::string& name) {
    scene_test::TempDir dir(name);
    return vplkit::scene::load_gltf(b.write(dir.path(), name, true));
}

scene_test::GltfBuilder float_quad() {
    scene_test::GltfBuilder b;
    b.roots.push_back(b.node("{\"mesh\":" + std::to_string(b.mesh("[" + scene_test::unit_quad(b) + "]")) + "}"));
    return b;
}

}  // namespace

TEST_CASE("gltf: quantized positions, normals and UVs load as the float quad") {
    const auto reference = load(float_quad(), "float");
    for (int type : {scene_test::kUnsignedShort, scene_test::kShort}) {
        CAPTURE(type);
        const auto scene = load(gltf_features::quantized_quad(type), "quantized");
        CHECK(vplkit::scene::warning_lines(scene.warnings).empty());
        REQUIRE(scene.vertices.size() == reference.vertices.size());
        for (size_t v = 0; v < scene.vertices.size(); ++v) {
            CAPTURE(v);
            CHECK(glm::length(scene.vertices[v].position - reference.vertices[v].position) <= 1e-6f);
            CHECK(glm::length(scene.vertices[v].normal - reference.vertices[v].normal) <= 1e-6f);
            CHECK(glm::length(scene.vertices[v].uv0 - reference.vertices[v].uv0) <= 1e-6f);
        }
    }
}

TEST_CASE("gltf: quantized positions render where the float version does") {
    const auto reference = gltf_features::read_gbuffer(load(float_quad(), "float"), 32, 32);
    const auto quantized =
        gltf_features::read_gbuffer(load(gltf_features::quantized_quad(scene_test::kShort), "quantized"), 32, 32);
    uint32_t covered = 0;
    float worst = 0.0f;
    for (size_t i = 0; i < reference.position.size(); ++i) {
        CHECK(quantized.position[i].w == reference.position[i].w);
        if (reference.position[i].w != 1.0f) continue;
        ++covered;
        worst = std::max(worst, glm::length(glm::vec3(quantized.position[i] - reference.position[i])));
    }
    CHECK(covered > 32 * 32 / 4);
    CHECK(worst <= 1e-6f);
}

TEST_CASE("gltf: integer positions in a file that does not declare KHR_mesh_quantization are refused by name") {
    try {
        load(gltf_features::quantized_quad(scene_test::kUnsignedShort, false), "undeclared");
        FAIL("loaded");
    } catch (const std::exception& e) {
        const std::string what = e.what();
        CHECK(what.find("POSITION of mesh 0 primitive 0") != std::string::npos);
        CHECK(what.find("only KHR_mesh_quantization allows them") != std::string::npos);
    }
}
