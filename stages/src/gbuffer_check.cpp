#include "vplkit/stages/gbuffer_check.hpp"

#include "vplkit/error.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>

namespace vplkit::stages {
namespace {

std::string percent(double share) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f%%", share * 100.0);
    return text;
}

// Whether `p`, projected back through the adapter's matrix, is behind the camera, not finite, or
// has a depth on or in front of the near plane or past the far plane.
bool outside_depth_range(const glm::mat4& view_projection, glm::vec3 p, DepthConvention convention) {
    const glm::vec4 h = view_projection * glm::vec4(p, 1.0f);
    if (!std::isfinite(h.z) || !std::isfinite(h.w) || !(h.w > 0.0f)) return true;
    const float depth = h.z / h.w;
    // The near plane's depth itself is the value a cleared depth of the other convention reads:
    // a surface there is a background pixel taken for geometry (the adapter pulls points toward
    // the viewer by 2 depth steps, so a small margin).
    constexpr float kNearMargin = 1e-5f;
    if (convention == DepthConvention::standard) return !(depth > kNearMargin) || depth > 1.0f;
    return !(depth < 1.0f - kNearMargin) || depth < 0.0f;
}

// The camera's rotation, view -> world (x right, y up, z backward, as lookAt's view space), from
// the directions in which clip x and -y (Vulkan's y points down the image) grow at the centre.
glm::mat3 camera_rotation(const glm::mat4& inverse_view_projection) {
    const auto unproject = [&](float x, float y) {
        const glm::vec4 h = inverse_view_projection * glm::vec4(x, y, 0.5f, 1.0f);
        return glm::vec3(h) / h.w;
    };
    const glm::vec3 centre = unproject(0.0f, 0.0f);
    const glm::vec3 right = glm::normalize(unproject(0.1f, 0.0f) - centre);
    const glm::vec3 up = glm::normalize(unproject(0.0f, -0.1f) - centre);
    return glm::mat3(right, up, glm::normalize(glm::cross(right, up)));
}

double angle_degrees(glm::vec3 a, glm::vec3 b) {
    return glm::degrees(std::acos(std::clamp(double(glm::dot(a, b)), -1.0, 1.0)));
}

double median(std::vector<double>& values) {
    if (values.empty()) return 0.0;
    const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

}  // namespace

GbufferCheck check_gbuffer_conventions(const GbufferReadback& images, const GbufferAdapterOptions& options,
                                       glm::vec3 eye) {
    const size_t n = images.position.size();
    if (n == 0 || images.normal.size() != n || images.geometric_normal.size() != n) {
        throw Error("gbuffer check: position, normal and geometric_normal must be non-empty and one size (" +
                    std::to_string(n) + ", " + std::to_string(images.normal.size()) + ", " +
                    std::to_string(images.geometric_normal.size()) + " pixels)");
    }
    const glm::mat4 view_projection = glm::inverse(options.inverse_view_projection);
    // The adapter's normal read in the other space: world -> view is undone by the camera's
    // rotation, view -> world by view_to_world's inverse.
    const glm::mat3 to_other_space = options.normal_space == GbufferNormalSpace::world
                                         ? camera_rotation(options.inverse_view_projection)
                                         : glm::transpose(options.view_to_world);
    size_t covered = 0, outside = 0, facing_away = 0, disagreeing = 0;
    std::vector<double> angles, other_angles, distances;
    for (size_t i = 0; i < n; ++i) {
        if (images.position[i].w != 1.0f) continue;
        ++covered;
        const glm::vec3 p(images.position[i]);
        if (outside_depth_range(view_projection, p, options.depth)) {
            ++outside;
            continue;
        }
        const glm::vec3 normal(images.normal[i]);
        const glm::vec3 geometric(images.geometric_normal[i]);
        if (glm::dot(normal, eye - p) < 0.0f) ++facing_away;
        if (!(glm::dot(normal, geometric) >= kGbufferCheckDisagreeCos)) ++disagreeing;
        angles.push_back(angle_degrees(normal, geometric));
        distances.push_back(glm::length(eye - p));
        other_angles.push_back(angle_degrees(glm::normalize(to_other_space * normal), geometric));
    }
    GbufferCheck check;
    check.pixels = n;
    check.options = options;
    check.covered_share = double(covered) / double(n);
    if (covered > 0) check.outside_share = double(outside) / double(covered);
    if (!angles.empty()) {
        check.facing_away_share = double(facing_away) / double(angles.size());
        check.disagreeing_share = double(disagreeing) / double(angles.size());
        check.median_angle_degrees = median(angles);
        check.other_space_median_angle_degrees = median(other_angles);
        // The camera centre maps to clip (0, 0, z, 0): it is the unprojection of that direction
        // (none, at infinity, for an orthographic projection).
        const glm::vec4 centre = options.inverse_view_projection * glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
        const double scale = median(distances);
        if (std::abs(centre.w) > 1e-6f * glm::length(glm::vec3(centre)) && scale > 0.0) {
            check.eye_offset = glm::length(glm::vec3(centre) / centre.w - eye) / scale;
        }
    }
    return check;
}

GbufferCheck check_gbuffer_conventions(const GbufferReadback& images, const GbufferAdapterOptions& adapter,
                                       const GiChainFrame& frame) {
    GbufferAdapterOptions options = adapter;  // as GiChain::add_frame_passes sets them
    options.inverse_view_projection = glm::inverse(frame.view_projection);
    options.view_to_world = frame.view_to_world;
    return check_gbuffer_conventions(images, options, frame.camera_position);
}

std::vector<std::string> GbufferCheck::problems() const {
    std::vector<std::string> found;
    const bool standard = options.depth == DepthConvention::standard;
    const std::string other_depth = standard ? "DepthConvention::reversed" : "DepthConvention::standard";
    if (covered_share == 0.0) {
        found.push_back("no pixel has a surface: every depth reads as the far plane. Is the depth " +
                        std::string(standard ? "reversed Z" : "standard Z") + " (set depth = " + other_depth +
                        "), and does the depth view read the renderer's depth aspect?");
        return found;
    }
    const bool positions_wrong = outside_share > kGbufferCheckMaxOutsideShare;
    if (positions_wrong) {
        found.push_back(percent(outside_share) +
                        " of the surfaces lie on or in front of the near plane, behind the camera or past the far "
                        "plane: is the depth " +
                        std::string(standard ? "reversed Z" : "standard Z") + " (set depth = " + other_depth +
                        ")? Is inverse_view_projection (GiChainFrame::view_projection) the inverse of the "
                        "projection x view the depth was rendered with?");
    }
    if (eye_offset > kGbufferCheckMaxEyeOffset) {
        char offset[32];
        std::snprintf(offset, sizeof offset, "%.1f%%", eye_offset * 100.0);
        found.push_back(std::string("the camera that inverse_view_projection describes is ") + offset +
                        " of the surfaces' distance away from the eye passed: is inverse_view_projection "
                        "(GiChainFrame::view_projection) the inverse of this frame's projection x view, the one "
                        "the depth was rendered with, and the eye (GiChainFrame::camera_position) the camera's "
                        "position?");
    }
    const bool normals_wrong = facing_away_share > kGbufferCheckMaxFacingAwayShare ||
                               disagreeing_share > kGbufferCheckMaxDisagreeingShare ||
                               median_angle_degrees > kGbufferCheckMaxMedianAngleDegrees;
    if (!normals_wrong) return found;
    char angles[96];
    std::snprintf(angles, sizeof angles, "median %.0f degrees (%.0f read in %s space)", median_angle_degrees,
                  other_space_median_angle_degrees,
                  options.normal_space == GbufferNormalSpace::world ? "view" : "world");
    const std::string measured = percent(facing_away_share) + " of the shading normals face away from the camera, " +
                                 percent(disagreeing_share) +
                                 " differ from the surface reconstructed from depth by more than 60 degrees, " +
                                 angles + ": ";
    if (median_angle_degrees <= kGbufferCheckMaxMedianAngleDegrees) {
        // The normals agree with the surfaces from depth, and both face away: the adapter's viewer
        // (from the depth convention and the matrix) is not where the camera is.
        found.push_back(percent(facing_away_share) +
                        " of the surfaces face away from the camera although their normals agree with the depth: "
                        "is the depth " +
                        std::string(standard ? "reversed Z" : "standard Z") + " (set depth = " + other_depth +
                        ")? Is inverse_view_projection (GiChainFrame::view_projection) the inverse of the "
                        "projection x view the depth was rendered with, and the eye (GiChainFrame::camera_position) "
                        "the camera's position?");
        return found;
    }
    const std::string first = positions_wrong ? " (the positions are wrong too: fix the depth first)" : "";
    // The other space explains the normals when reading them so halves the angle.
    if (other_space_median_angle_degrees < 0.5 * median_angle_degrees) {
        found.push_back(measured +
                        (options.normal_space == GbufferNormalSpace::world
                             ? "are they in view space (set normal_space = GbufferNormalSpace::view and view_to_world, "
                               "or GiChainFrame::view_to_world / GiChainFrame::from_camera)?"
                             : "are they in world space (set normal_space = GbufferNormalSpace::world), or is "
                               "view_to_world (GiChainFrame::view_to_world) not the camera's rotation?") +
                        first);
    } else {
        found.push_back(measured +
                        "is normal_encoding the normal image's layout (xyz: n; xyz_unorm: n * 0.5 + 0.5; "
                        "octahedral; octahedral_unorm: octahedral * 0.5 + 0.5)? Or is inverse_view_projection not the "
                        "inverse of the projection x view the depth was rendered with (the surfaces from depth are "
                        "then bent)?" +
                        (options.normal_space == GbufferNormalSpace::view
                             ? " Is view_to_world (GiChainFrame::view_to_world) the camera's rotation, view to world?"
                             : "") +
                        first);
    }
    return found;
}

}  // namespace vplkit::stages
