#include "scene/gltf_geometry.hpp"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <utility>

namespace vplkit::scene::detail {
namespace {

glm::vec3 any_orthogonal(glm::vec3 n) {
    const glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    return glm::normalize(a - n * glm::dot(n, a));
}

// A triangle whose height over its longest edge is below float resolution of that edge has no
// plane that float arithmetic can resolve (its geometric normal would be rounding noise):
// it counts as zero area. |e1 x e2| = base * height, and base^2 is the longest edge squared.
bool degenerate(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    const glm::dvec3 e1 = b - a, e2 = c - a, e3 = c - b;
    const double twice_area = glm::length(glm::cross(e1, e2));
    const double longest2 = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
    return !(twice_area > double(FLT_EPSILON) * longest2);
}

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

uint32_t generate_tangents(std::span<Vertex> vertices, std::span<const uint32_t> triangles) {
    std::vector<glm::dvec3> tangent_sum(vertices.size(), glm::dvec3(0.0));
    std::vector<glm::dvec3> bitangent_sum(vertices.size(), glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
        const uint32_t i[3] = {triangles[t], triangles[t + 1], triangles[t + 2]};
        const glm::dvec3 p0(vertices[i[0]].position), p1(vertices[i[1]].position), p2(vertices[i[2]].position);
        const glm::dvec2 w0(vertices[i[0]].uv0), w1(vertices[i[1]].uv0), w2(vertices[i[2]].uv0);
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
        const double du1 = w1.x - w0.x, dv1 = w1.y - w0.y, du2 = w2.x - w0.x, dv2 = w2.y - w0.y;
        // Solving e1 = du1 T + dv1 B, e2 = du2 T + dv2 B for T = dP/du and B = dP/dv.
        const double r = du1 * dv2 - du2 * dv1;
        if (r == 0.0 || !std::isfinite(r)) continue;  // UVs without area: no gradient
        const glm::dvec3 dp_du = (e1 * dv2 - e2 * dv1) / r;
        const glm::dvec3 dp_dv = (e2 * du1 - e1 * du2) / r;
        const double lt = glm::length(dp_du), lb = glm::length(dp_dv);
        if (!(lt > 0.0) || !(lb > 0.0) || !std::isfinite(lt) || !std::isfinite(lb)) continue;
        // Unit directions weighted by area: a triangle's UV scale should not decide its weight.
        const double area = 0.5 * glm::length(glm::cross(e1, e2));
        for (uint32_t k : i) {
            tangent_sum[k] += dp_du * (area / lt);
            bitangent_sum[k] += dp_dv * (area / lb);
        }
    }
    uint32_t undefined = 0;
    for (size_t v = 0; v < vertices.size(); ++v) {
        const glm::dvec3 n(vertices[v].normal);
        const glm::dvec3 sum = tangent_sum[v];
        const glm::dvec3 t = sum - n * glm::dot(n, sum);  // Gram-Schmidt
        const double sum_length = glm::length(sum);
        const double t_length = glm::length(t);
        if (!(sum_length > 0.0) || !(t_length > 1e-6 * sum_length)) {
            vertices[v].tangent = glm::vec4(any_orthogonal(vertices[v].normal), 1.0f);
            ++undefined;
            continue;
        }
        // glTF UVs have v growing downward in the image while normal maps store "up in the image"
        // in green, so the bitangent w * cross(n, t) must point where v decreases: against dP/dv.
        const double w = glm::dot(glm::cross(n, t), bitangent_sum[v]) > 0.0 ? -1.0 : 1.0;
        vertices[v].tangent = glm::vec4(glm::vec3(t / t_length), float(w));
    }
    return undefined;
}

void append_instance(const GltfSource& source, Scene& scene, const PrimitiveData& data, const glm::dmat4& world,
                     bool wants_tangents, PrimitiveInstance info, const std::string& where) {
    info.material = data.material;
    const size_t triangle_count = data.indices.size() / 3;
    const glm::dmat3 linear(world);
    const double det = glm::determinant(linear);
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) {
        // A singular transform (a zero scale) flattens every triangle.
        scene.warnings.degenerate_triangles += uint32_t(triangle_count);
        return;
    }
    info.mirrored = det < 0.0;
    // Normals transform with the inverse transpose so they stay orthogonal to the surface under
    // non-uniform scale.
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));

    std::vector<glm::vec3> positions(data.positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        positions[i] = glm::vec3(world * glm::dvec4(glm::dvec3(data.positions[i]), 1.0));
        if (!finite(positions[i])) {
            source.fail(where + ": vertex " + std::to_string(i) +
                        " is not finite in world space (the node transform overflows float)");
        }
    }

    // Triangles kept, counter-clockwise in world space: a mirroring transform reverses the
    // winding, so two corners are swapped to keep the front face where the file put it.
    std::vector<uint32_t> kept;
    kept.reserve(data.indices.size());
    for (size_t t = 0; t < triangle_count; ++t) {
        uint32_t a = data.indices[3 * t], b = data.indices[3 * t + 1], c = data.indices[3 * t + 2];
        if (info.mirrored) std::swap(b, c);
        if (a == b || b == c || a == c ||
            degenerate(glm::dvec3(positions[a]), glm::dvec3(positions[b]), glm::dvec3(positions[c]))) {
            ++scene.warnings.degenerate_triangles;
            continue;
        }
        kept.insert(kept.end(), {a, b, c});
    }
    if (kept.empty()) return;

    const bool has_uvs = !data.uvs.empty();
    const bool has_tangents = !data.tangents.empty();
    const uint32_t base = uint32_t(scene.vertices.size());
    std::vector<uint32_t> local;  // the kept triangles' vertices, relative to `base`
    std::vector<Vertex>& out = scene.vertices;

    auto file_tangent = [&](uint32_t i, glm::vec3 normal) {
        const glm::vec4 t = data.tangents[i];
        glm::dvec3 xyz = linear * glm::dvec3(t);
        xyz -= glm::dvec3(normal) * glm::dot(glm::dvec3(normal), xyz);
        const double length = glm::length(xyz);
        // A mirroring transform flips the handedness of the tangent frame.
        const float w = (t.w < 0.0f ? -1.0f : 1.0f) * (info.mirrored ? -1.0f : 1.0f);
        if (!(length > 0.0)) return glm::vec4(any_orthogonal(normal), w);
        return glm::vec4(glm::vec3(xyz / length), w);
    };

    if (data.normals.empty()) {
        // glTF 2.0 (3.7.2.1): without normals a client must use flat normals, so no vertex is
        // shared between triangles.
        info.normals = NormalSource::generated_flat;
        for (size_t k = 0; k < kept.size(); k += 3) {
            const glm::dvec3 p0(positions[kept[k]]), p1(positions[kept[k + 1]]), p2(positions[kept[k + 2]]);
            const glm::vec3 normal(glm::normalize(glm::cross(p1 - p0, p2 - p0)));
            for (size_t j = 0; j < 3; ++j) {
                const uint32_t i = kept[k + j];
                Vertex v;
                v.position = positions[i];
                v.normal = normal;
                if (has_uvs) v.uv0 = data.uvs[i];
                if (!data.uvs1.empty()) v.uv1 = data.uvs1[i];
                if (!data.colors.empty()) v.color = data.colors[i];
                if (has_tangents) v.tangent = file_tangent(i, normal);
                out.push_back(v);
                scene.vertex_random.push_back(vertex_random_value(info.node, info.mesh, info.primitive, i));
                local.push_back(uint32_t(k + j));
            }
        }
    } else {
        info.normals = NormalSource::file;
        std::vector<uint32_t> zero_normals;
        for (size_t i = 0; i < positions.size(); ++i) {
            Vertex v;
            v.position = positions[i];
            const glm::dvec3 n = normal_matrix * glm::dvec3(data.normals[i]);
            const double length = glm::length(n);
            if (length > 0.0 && std::isfinite(length)) {
                v.normal = glm::vec3(n / length);
            } else {
                zero_normals.push_back(uint32_t(i));
            }
            if (has_uvs) v.uv0 = data.uvs[i];
            if (!data.uvs1.empty()) v.uv1 = data.uvs1[i];
            if (!data.colors.empty()) v.color = data.colors[i];
            out.push_back(v);
            scene.vertex_random.push_back(vertex_random_value(info.node, info.mesh, info.primitive, uint32_t(i)));
        }
        if (!zero_normals.empty()) {
            // Exporters write zero normals for vertices they could not shade: use the area-weighted
            // normal of the kept triangles around the vertex instead.
            std::vector<glm::dvec3> face_sum(positions.size(), glm::dvec3(0.0));
            for (size_t k = 0; k < kept.size(); k += 3) {
                const glm::dvec3 p0(positions[kept[k]]), p1(positions[kept[k + 1]]), p2(positions[kept[k + 2]]);
                const glm::dvec3 face = glm::cross(p1 - p0, p2 - p0);
                for (size_t j = 0; j < 3; ++j) face_sum[kept[k + j]] += face;
            }
            for (uint32_t i : zero_normals) {
                const double length = glm::length(face_sum[i]);
                out[base + i].normal = length > 0.0 ? glm::vec3(face_sum[i] / length) : glm::vec3(0.0f, 0.0f, 1.0f);
            }
            scene.warnings.repaired_normals += uint32_t(zero_normals.size());
        }
        if (has_tangents) {
            for (size_t i = 0; i < positions.size(); ++i) {
                out[base + i].tangent = file_tangent(uint32_t(i), out[base + i].normal);
            }
        }
        local = kept;
    }

    info.vertex_count = uint32_t(out.size()) - base;
    if (has_tangents) {
        info.tangents = TangentSource::file;
    } else if (wants_tangents) {
        info.tangents = TangentSource::generated;
        scene.warnings.untangented_vertices +=
            generate_tangents(std::span<Vertex>(out).subspan(base, info.vertex_count), local);
    }

    info.first_vertex = base;
    info.first_triangle = uint32_t(scene.indices.size() / 3);
    info.triangle_count = uint32_t(local.size() / 3);
    for (uint32_t i : local) scene.indices.push_back(base + i);
    scene.triangle_materials.insert(scene.triangle_materials.end(), info.triangle_count, info.material);
    scene.primitives.push_back(info);
}

}  // namespace vplkit::scene::detail
