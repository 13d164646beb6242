#include "vplkit/shadow_map.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/rsm_shade.hpp"
#include "vplkit/stages/gbuffer.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace vplkit {
namespace {

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::array<glm::vec3, 8> corners(const scene::Bounds& b) {
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i) {
        c[i] = {(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z};
    }
    return c;
}

// A view (right-handed, looking down -Z) from `eye` along `forward`, with an up vector that is
// not parallel to it.
glm::mat4 view_along(glm::vec3 eye, glm::vec3 forward) {
    const glm::vec3 up = std::abs(forward.y) > 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    return scene::look_at(eye, eye + forward, up, 1.0f).view();
}

// Near and far planes of a perspective view from `eye` that hold the whole box: far just past
// the farthest corner, near a fixed fraction of it (float depth keeps about 1e-3 relative
// precision at 1e-4 near/far; geometry nearer than that to a light is clipped).
std::pair<float, float> perspective_range(glm::vec3 eye, const scene::Bounds& bounds) {
    float farthest = 0.0f;
    for (const glm::vec3& c : corners(bounds)) farthest = std::max(farthest, glm::length(c - eye));
    const float far_plane = std::max(1.01f * farthest, 1e-30f);
    return {1e-4f * far_plane, far_plane};
}

}  // namespace

ShadowMap ShadowMap::create(Context& context, const scene::Light& light, const scene::Bounds& bounds,
                            uint32_t face_resolution) {
    if (face_resolution == 0) throw Error("shadow map: resolution 0");
    if (!finite(light.color) || !std::isfinite(light.intensity) || light.intensity < 0.0f || light.color.x < 0.0f ||
        light.color.y < 0.0f || light.color.z < 0.0f) {
        throw Error("shadow map: light '" + light.name + "' has a negative or non-finite colour or intensity");
    }
    const bool directed = light.type != scene::LightType::point;
    const float direction_length = glm::length(light.direction);
    if (directed && (!finite(light.direction) || !(direction_length > 0.0f))) {
        throw Error("shadow map: light '" + light.name + "' has no direction");
    }
    if (light.type != scene::LightType::directional && !finite(light.position)) {
        throw Error("shadow map: light '" + light.name + "' has a non-finite position");
    }
    const glm::vec3 direction = directed ? light.direction / direction_length : glm::vec3(0.0f, 0.0f, -1.0f);

    ShadowMap map;
    map.light = light;
    map.face_resolution = face_resolution;
    shaders::RsmLight uniform{};
    const glm::vec3 intensity = light.color * light.intensity;
    uniform.intensity = {intensity.x, intensity.y, intensity.z};
    uniform.type = uint32_t(light.type);
    uniform.position = {light.position.x, light.position.y, light.position.z};
    uniform.range = light.range;
    uniform.direction = {direction.x, direction.y, direction.z};
    uniform.face_texels = float(face_resolution);
    const float n = float(face_resolution);

    const bool cube =
        light.type == scene::LightType::point ||
        (light.type == scene::LightType::spot && light.outer_cone_angle > stages::kSpotSingleFaceMaxAngle);
    if (light.type == scene::LightType::directional) {
        // Orthographic, fitted to the box: view space centred on it, x/y the box's projection
        // perpendicular to the light, depth the signed distance along the light.
        const glm::vec3 centre = bounds.center();
        const glm::mat4 view = view_along(centre, direction);
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (const glm::vec3& c : corners(bounds)) {
            const glm::vec3 v = glm::vec3(view * glm::vec4(c, 1.0f));
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        const float diagonal = std::max(glm::length(bounds.extent()), 1e-30f);
        // A scene seen exactly edge-on has no extent along one axis; give it a sliver.
        for (int axis = 0; axis < 2; ++axis) {
            const float missing = 1e-6f * diagonal - (hi[axis] - lo[axis]);
            if (missing > 0.0f) {
                lo[axis] -= 0.5f * missing;
                hi[axis] += 0.5f * missing;
            }
        }
        // Depth: distance along the light d = -z, padded so that a flat scene facing the light
        // (zero depth range) is not clipped by the near or far plane.
        const float margin = 1e-3f * diagonal;
        const float near_d = -hi.z - margin, far_d = -lo.z + margin;
        glm::mat4 ortho(0.0f);
        ortho[0][0] = 2.0f / (hi.x - lo.x);
        ortho[3][0] = -(hi.x + lo.x) / (hi.x - lo.x);
        ortho[1][1] = -2.0f / (hi.y - lo.y);  // y down the image
        ortho[3][1] = (hi.y + lo.y) / (hi.y - lo.y);
        ortho[2][2] = -1.0f / (far_d - near_d);  // depth = (-z - near) / (far - near)
        ortho[3][2] = -near_d / (far_d - near_d);
        ortho[3][3] = 1.0f;
        map.faces.push_back({ortho * view, {{0, 0}, {face_resolution, face_resolution}}});
        map.near_plane = near_d;
        map.far_plane = far_d;
        map.texel_area = ((hi.x - lo.x) / n) * ((hi.y - lo.y) / n);
        uniform.texel_area = map.texel_area;
    } else {
        const auto [near_plane, far_plane] = perspective_range(light.position, bounds);
        map.near_plane = near_plane;
        map.far_plane = far_plane;
        if (cube) {
            const float quarter_turn = 0.5f * std::numbers::pi_v<float>;
            const glm::mat4 projection = stages::vulkan_perspective(quarter_turn, 1.0f, near_plane, far_plane);
            const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
            for (uint32_t f = 0; f < 6; ++f) {
                const VkRect2D rect = {{int32_t((f % 3) * face_resolution), int32_t((f / 3) * face_resolution)},
                                       {face_resolution, face_resolution}};
                map.faces.push_back({projection * view_along(light.position, axes[f]), rect});
            }
            uniform.tan_half_fov = 1.0f;
        } else {
            const float outer = light.outer_cone_angle;
            if (!(outer > 0.0f)) throw Error("shadow map: spot light '" + light.name + "' has no cone");
            map.faces.push_back({stages::vulkan_perspective(2.0f * outer, 1.0f, near_plane, far_plane) *
                                     view_along(light.position, direction),
                                 {{0, 0}, {face_resolution, face_resolution}}});
            uniform.tan_half_fov = std::tan(outer);
        }
        if (light.type == scene::LightType::spot) {
            // KHR_lights_punctual spot falloff (its recommended implementation).
            const float cos_outer = std::cos(light.outer_cone_angle);
            const float scale = 1.0f / std::max(0.001f, std::cos(light.inner_cone_angle) - cos_outer);
            uniform.spot_scale = scale;
            uniform.spot_offset = -cos_outer * scale;
        }
    }

    const uint32_t width = cube ? 3 * face_resolution : face_resolution;
    const uint32_t height = cube ? 2 * face_resolution : face_resolution;
    const std::string label = "shadow map '" + light.name + "' ";
    constexpr VkImageUsageFlags color =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    map.position = Image::create(context, width, height, stages::kRsmPositionFormat, color, label + "position");
    map.normal = Image::create(context, width, height, stages::kRsmNormalFormat, color, label + "normal");
    map.flux = Image::create(context, width, height, stages::kRsmFluxFormat, color, label + "flux");
    map.depth =
        Image::create(context, width, height, stages::kShadowDepthFormat,
                      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, label + "depth");
    map.light_uniform = Buffer::create(context, sizeof(uniform), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::device,
                                       label + "light");
    map.light_uniform.upload(&uniform, sizeof(uniform));
    return map;
}

std::vector<stages::ShadowMapViews> shadow_map_views(std::span<ShadowMap> maps) {
    std::vector<stages::ShadowMapViews> views;
    for (ShadowMap& map : maps) views.push_back(map);
    return views;
}

void add_shadow_map_passes(stages::Device& device, StepList& passes, const stages::SceneBuffers& scene,
                           std::span<ShadowMap> maps) {
    const std::vector<stages::ShadowMapViews> views = shadow_map_views(maps);
    stages::add_shadow_map_passes(device, passes, scene, std::span<const stages::ShadowMapViews>(views));
}

}  // namespace vplkit
