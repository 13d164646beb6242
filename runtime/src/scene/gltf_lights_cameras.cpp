// Lights and cameras: each parameter the file states checked against glTF 2.0's ranges
// (KHR_lights_punctual for lights, glTF 2.0's camera properties for cameras) before it is used.

#include "scene/gltf_lights_cameras.hpp"

#include "scene/gltf_checks.hpp"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <numbers>

namespace vplkit::scene::detail {

Light convert_light(const GltfSource& source, int index, const glm::dmat4& world, const std::string& node_label) {
    const tinygltf::Light& l = source.model.lights[size_t(index)];
    const std::string label = "light " + std::to_string(index) + quoted_name(l.name) + " (on " + node_label + ")";
    Light out;
    out.origin = LightOrigin::file;
    out.name = l.name.empty() ? "light " + std::to_string(index) : l.name;
    if (l.type == "directional") {
        out.type = LightType::directional;
    } else if (l.type == "point") {
        out.type = LightType::point;
    } else if (l.type == "spot") {
        out.type = LightType::spot;
    } else {
        source.fail(label + ": type '" + l.type + "' is not directional, point or spot");
    }
    if (!l.color.empty()) {
        if (l.color.size() != 3) source.fail(label + ": color does not have 3 components");
        for (int c = 0; c < 3; ++c) {
            if (!finite(l.color[size_t(c)]) || l.color[size_t(c)] < 0.0)
                source.fail(label + ": color is negative or not finite");
            out.color[c] = float(l.color[size_t(c)]);
        }
    }
    if (!finite(l.intensity) || l.intensity < 0.0) source.fail(label + ": intensity is negative or not finite");
    out.intensity = float(l.intensity);
    if (!finite(l.range) || l.range < 0.0) source.fail(label + ": range is negative or not finite");
    out.range = float(l.range);
    if (out.type == LightType::spot) {
        const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
        // Tolerance for exporters that write pi/2 rounded up in the last digit.
        if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2 + 1e-6)) {
            source.fail(label + ": cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
        }
        out.inner_cone_angle = float(inner);
        out.outer_cone_angle = float(std::min(outer, std::numbers::pi / 2));
    }
    out.position = glm::vec3(world[3]);
    const glm::dvec3 direction = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const double length = glm::length(direction);
    if (out.type != LightType::point && !(length > 0.0)) {
        source.fail(label + ": the node's transform has a zero scale, so the light has no direction");
    }
    if (length > 0.0) out.direction = glm::vec3(direction / length);
    return out;
}

Camera convert_camera(const GltfSource& source, int index, const glm::dmat4& world, const std::string& node_label) {
    const tinygltf::Camera& c = source.model.cameras[size_t(index)];
    const std::string label = "camera " + std::to_string(index) + quoted_name(c.name) + " (on " + node_label + ")";
    Camera out;
    if (c.type == "perspective") {
        const auto& p = c.perspective;
        if (!(finite(p.yfov) && p.yfov > 0.0 && p.yfov < std::numbers::pi))
            source.fail(label + ": yfov is not in (0, pi)");
        if (!(finite(p.znear) && p.znear > 0.0)) source.fail(label + ": znear is not > 0");
        if (!(finite(p.zfar) && (p.zfar == 0.0 || p.zfar > p.znear))) source.fail(label + ": zfar is not > znear");
        if (!(finite(p.aspectRatio) && p.aspectRatio >= 0.0)) source.fail(label + ": aspectRatio is negative");
        out.projection = Projection::perspective;
        out.yfov = float(p.yfov);
        out.aspect = float(p.aspectRatio);
        out.znear = float(p.znear);
        out.zfar = float(p.zfar);
    } else if (c.type == "orthographic") {
        const auto& o = c.orthographic;
        // glTF 2.0 5.13: xmag and ymag must not be 0, zfar must be > znear >= 0.
        if (!(finite(o.xmag) && o.xmag > 0.0 && finite(o.ymag) && o.ymag > 0.0)) {
            source.fail(label + ": orthographic xmag and ymag must be > 0 (half the view's width and height)");
        }
        if (!(finite(o.znear) && o.znear >= 0.0)) source.fail(label + ": orthographic znear is not >= 0");
        if (!(finite(o.zfar) && o.zfar > o.znear)) source.fail(label + ": orthographic zfar is not > znear");
        out.projection = Projection::orthographic;
        out.xmag = float(o.xmag);
        out.ymag = float(o.ymag);
        out.znear = float(o.znear);
        out.zfar = float(o.zfar);
    } else {
        source.fail(label + ": type '" + c.type + "' is neither perspective nor orthographic");
    }
    const glm::dmat3 linear(world);
    const glm::dvec3 forward = linear * glm::dvec3(0.0, 0.0, -1.0);
    const glm::dvec3 up = linear * glm::dvec3(0.0, 1.0, 0.0);
    const double forward_length = glm::length(forward);
    const glm::dvec3 f = forward / forward_length;
    const glm::dvec3 u = up - f * glm::dot(f, up);
    const double up_length = glm::length(u);
    if (!(forward_length > 0.0) || !(up_length > 0.0)) {
        source.fail(label + ": the node's transform is singular, so the camera has no orientation");
    }
    out.name = c.name.empty() ? "camera " + std::to_string(index) : c.name;
    out.origin = CameraOrigin::file;
    out.position = glm::vec3(world[3]);
    out.forward = glm::vec3(f);
    out.up = glm::vec3(u / up_length);
    return out;
}

}  // namespace vplkit::scene::detail
