// renderer_mesh.hpp: an indexed mesh (shared vertices, 16- and 32-bit indices, the renderer's own
// vertex struct) as the triangle list and per-triangle albedo renderer_scene takes, and the errors
// for a count that is not a triangle list and an index past the vertices.

#include "vplkit/error.hpp"
#include "vplkit/stages/renderer_mesh.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

namespace {

struct RendererVertex {  // a renderer's interleaved vertex: the position not first
    glm::vec3 normal;
    glm::vec3 position;
    glm::vec3 colour;
};

// A quad of four shared vertices, two triangles (0 1 2, 0 2 3); vertex 3 of another colour.
const std::vector<RendererVertex> kQuad = {{{0, 1, 0}, {0, 0, 0}, {0.3f, 0.3f, 0.3f}},
                                           {{0, 1, 0}, {1, 0, 0}, {0.3f, 0.3f, 0.3f}},
                                           {{0, 1, 0}, {1, 0, 1}, {0.3f, 0.3f, 0.3f}},
                                           {{0, 1, 0}, {0, 0, 1}, {0.9f, 0.6f, 0.0f}}};

}  // namespace

TEST_CASE("renderer mesh: an indexed quad as 6 triangle-list vertices and 2 per-triangle albedos") {
    const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
    const std::vector<glm::vec3> triangles =
        vplkit::stages::triangles_from_indexed(kQuad, indices, &RendererVertex::position);
    const std::vector<glm::vec3> expected = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 0}, {1, 0, 1}, {0, 0, 1}};
    CHECK(triangles == expected);

    const std::vector<uint16_t> short_indices = {0, 1, 2, 0, 2, 3};
    std::vector<glm::vec3> positions;
    for (const RendererVertex& v : kQuad) positions.push_back(v.position);
    CHECK(vplkit::stages::triangles_from_indexed(positions, short_indices) == expected);

    const std::vector<glm::vec3> albedo =
        vplkit::stages::per_triangle_from_indexed(kQuad, indices, &RendererVertex::colour);
    REQUIRE(albedo.size() == 2);
    CHECK(albedo[0] == glm::vec3(0.3f));  // all three vertices share it
    CHECK(albedo[1].x == doctest::Approx((0.3 + 0.3 + 0.9) / 3.0));
    CHECK(albedo[1].y == doctest::Approx((0.3 + 0.3 + 0.6) / 3.0));
    CHECK(albedo[1].z == doctest::Approx(0.6 / 3.0));
}

TEST_CASE("renderer mesh: a count that is not a triangle list and an index past the vertices are errors") {
    const std::vector<uint32_t> seven = {0, 1, 2, 0, 2, 3, 1};
    CHECK_THROWS_WITH_AS(vplkit::stages::triangles_from_indexed(kQuad, seven, &RendererVertex::position),
                         "indexed mesh: 7 indices, not a multiple of 3 (a triangle list is 3 indices a triangle)",
                         vplkit::Error);
    const std::vector<uint32_t> past = {0, 1, 2, 0, 2, 4};
    CHECK_THROWS_WITH_AS(vplkit::stages::per_triangle_from_indexed(kQuad, past, &RendererVertex::colour),
                         "indexed mesh: index 5 (triangle 1) is 4, past the 4 vertices", vplkit::Error);
}
