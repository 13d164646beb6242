#include "vpl_sources.hpp"

#include "vplkit/error.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace vplkit::cli {

std::vector<shaders::Vpl> random_vpls(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::normal_distribution<float> gauss;
    std::vector<shaders::Vpl> vpls(count);
    for (shaders::Vpl& vpl : vpls) {
        vpl.position = {unit(rng), unit(rng), unit(rng)};
        float x = gauss(rng), y = gauss(rng), z = gauss(rng);
        float length = std::max(std::sqrt(x * x + y * y + z * z), 1e-20f);
        vpl.normal = {x / length, y / length, z / length};
        vpl.flux = {1.0f, 1.0f, 1.0f};
    }
    return vpls;
}

std::vector<shaders::Vpl> surface_vpls(const scene::Scene& scene, uint32_t count, uint32_t seed) {
    const size_t triangles = scene.triangle_count();
    std::vector<double> cumulative_area(triangles);
    double total = 0.0;
    for (size_t t = 0; t < triangles; ++t) {
        const glm::vec3 a = scene.vertices[scene.indices[3 * t]].position;
        const glm::vec3 b = scene.vertices[scene.indices[3 * t + 1]].position;
        const glm::vec3 c = scene.vertices[scene.indices[3 * t + 2]].position;
        total += 0.5 * double(glm::length(glm::cross(b - a, c - a)));
        cumulative_area[t] = total;
    }
    if (!(total > 0.0)) {
        throw Error("surface VPLs: the scene " + scene.source.string() + " has no surface area");
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<shaders::Vpl> vpls(count);
    for (shaders::Vpl& vpl : vpls) {
        const double pick = unit(rng) * total;
        const size_t t = std::min(
            size_t(std::lower_bound(cumulative_area.begin(), cumulative_area.end(), pick) - cumulative_area.begin()),
            triangles - 1);
        const glm::vec3 a = scene.vertices[scene.indices[3 * t]].position;
        const glm::vec3 b = scene.vertices[scene.indices[3 * t + 1]].position;
        const glm::vec3 c = scene.vertices[scene.indices[3 * t + 2]].position;
        // Uniform on the triangle: the square-root warp of two uniform numbers.
        const float su = float(std::sqrt(unit(rng))), v = float(unit(rng));
        const glm::vec3 p = a * (1.0f - su) + b * (su * (1.0f - v)) + c * (su * v);
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        const glm::vec4 color = scene.materials[scene.triangle_materials[t]].base_color_factor;
        vpl.position = {p.x, p.y, p.z};
        vpl.normal = {n.x, n.y, n.z};
        vpl.flux = {color.x / float(count), color.y / float(count), color.z / float(count)};
    }
    return vpls;
}

}  // namespace vplkit::cli
