#pragma once
// A renderer's indexed mesh (vertex and index buffers, shared vertices) as the triangle list the
// kit's scene takes: renderer_scene, vpl_sources_from_renderer and build_bvh read 3 vertices a
// triangle (RendererSurfaces::triangles) and one albedo a triangle (triangle_albedo), because a
// BVH leaf and a VPL hit carry no index buffer. From the renderer's own vertex struct:
//
//   const auto triangles = vplkit::stages::triangles_from_indexed(mesh.vertices, mesh.indices, &Vertex::position);
//   const auto albedo = vplkit::stages::per_triangle_from_indexed(mesh.vertices, mesh.indices, &Vertex::albedo);
//   auto scene = vplkit::stages::renderer_scene(lights, {}, {triangles, albedo});
//
// Both throw vplkit::Error naming the problem when the index count is not a multiple of 3 or an
// index is past the vertices (a hand-written loop reads past the array instead).

#include "vplkit/error.hpp"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <ranges>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace vplkit::stages {

namespace detail {

// The index list as a span of its own unsigned type (uint16_t or uint32_t), after the checks.
template <std::ranges::contiguous_range Indices>
auto triangle_list(const Indices& indices, size_t vertex_count) {
    using Index = std::remove_cv_t<std::ranges::range_value_t<Indices>>;
    static_assert(std::is_integral_v<Index> && std::is_unsigned_v<Index>, "16- or 32-bit unsigned indices");
    const std::span<const Index> list(std::ranges::data(indices), std::ranges::size(indices));
    if (list.size() % 3 != 0) {
        throw Error("indexed mesh: " + std::to_string(list.size()) +
                    " indices, not a multiple of 3 (a triangle list is 3 indices a triangle)");
    }
    for (size_t i = 0; i < list.size(); ++i) {
        if (size_t(list[i]) >= vertex_count) {
            throw Error("indexed mesh: index " + std::to_string(i) + " (triangle " + std::to_string(i / 3) + ") is " +
                        std::to_string(size_t(list[i])) + ", past the " + std::to_string(vertex_count) + " vertices");
        }
    }
    return list;
}

}  // namespace detail

// Each triangle's three positions, in index order: 3 x (indices.size() / 3) vertices. `vertices`
// and `indices`: any contiguous range (std::vector, std::span, array) of the renderer's vertex
// struct and of uint16_t or uint32_t.
template <std::ranges::contiguous_range Vertices, std::ranges::contiguous_range Indices, class Vertex>
std::vector<glm::vec3> triangles_from_indexed(const Vertices& vertices, const Indices& indices,
                                              glm::vec3 Vertex::*position) {
    const std::span<const Vertex> v(std::ranges::data(vertices), std::ranges::size(vertices));
    std::vector<glm::vec3> triangles;
    for (size_t i : detail::triangle_list(indices, v.size())) triangles.push_back(v[i].*position);
    return triangles;
}

// Positions in an array of their own (glm::vec3 each).
template <std::ranges::contiguous_range Positions, std::ranges::contiguous_range Indices>
std::vector<glm::vec3> triangles_from_indexed(const Positions& positions, const Indices& indices) {
    const std::span<const glm::vec3> p(std::ranges::data(positions), std::ranges::size(positions));
    std::vector<glm::vec3> triangles;
    for (size_t i : detail::triangle_list(indices, p.size())) triangles.push_back(p[i]);
    return triangles;
}

// One value a triangle from a per-vertex one (a vertex colour as the diffuse albedo): the mean
// of its three vertices' (the value itself where they share it, as on a flat-coloured mesh).
template <std::ranges::contiguous_range Vertices, std::ranges::contiguous_range Indices, class Vertex>
std::vector<glm::vec3> per_triangle_from_indexed(const Vertices& vertices, const Indices& indices,
                                                 glm::vec3 Vertex::*value) {
    const std::span<const Vertex> v(std::ranges::data(vertices), std::ranges::size(vertices));
    const auto list = detail::triangle_list(indices, v.size());
    std::vector<glm::vec3> per_triangle;
    for (size_t t = 0; t < list.size(); t += 3) {
        per_triangle.push_back((v[list[t]].*value + v[list[t + 1]].*value + v[list[t + 2]].*value) / 3.0f);
    }
    return per_triangle;
}

}  // namespace vplkit::stages
