#pragma once
// A one-call check of the G-buffer adapter's conventions (gbuffer_adapter.hpp), for a renderer
// while it integrates the kit (once, not per frame). A wrong option there (reversed Z declared
// standard, view-space normals declared world, another normal encoding, a wrong inverse
// view-projection) raises no error: the indirect light is just wrong. This reads the adapter's
// output and says which option is the likely culprit.
//
// Usage: run the adapter pass once, copy the kit's position, normal and geometric_normal images
// (RGBA32F, gbuffer_views.hpp) to host memory (vkCmdCopyImageToBuffer to a mapped buffer), then
//   GbufferCheck c = check_gbuffer_conventions({position, normal, geometric_normal}, options, eye);
//   for (const std::string& p : c.problems()) log(p);
// on a frame where the camera sees ordinary geometry (most surfaces of a scene face the camera).
// With GiChain: the images of chain.gbuffer(), and (GiChainOptions::adapter, the GiChainFrame).

#include "vplkit/stages/gbuffer_adapter.hpp"
#include "vplkit/stages/gi_chain.hpp"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace vplkit::stages {

// Host copies of the adapter's output images, row by row, one vec4 per pixel, all one size.
struct GbufferReadback {
    std::span<const glm::vec4> position;
    std::span<const glm::vec4> normal;
    std::span<const glm::vec4> geometric_normal;
};

// Thresholds, from the adapter's output on the Cornell box (tests/raster/test_gbuffer_check.cpp
// prints them). Correct options: 0% outside, 0% facing away, 1.3% over 60 degrees (edges),
// median angle 0, eye offset 1e-7. Wrong ones: reversed Z declared standard 30% outside (the
// cleared background) and 100% facing away; view-space normals declared world median 10 degrees
// (0 read in view space); n * 0.5 + 0.5 read as n 26% over 60 degrees, median 35; n read as
// n * 0.5 + 0.5 62% facing away, median 55; last frame's matrix (5 cm aside) eye offset 1.4%.
inline constexpr double kGbufferCheckMaxOutsideShare = 0.02;
inline constexpr double kGbufferCheckMaxFacingAwayShare = 0.1;
inline constexpr double kGbufferCheckMaxDisagreeingShare = 0.1;
inline constexpr double kGbufferCheckMaxMedianAngleDegrees = 5.0;
inline constexpr double kGbufferCheckMaxEyeOffset = 1e-3;
// A shading normal disagrees with the surface from depth beyond this angle (cos 60 degrees).
inline constexpr float kGbufferCheckDisagreeCos = 0.5f;

struct GbufferCheck {
    size_t pixels = 0;
    // Shares of all pixels.
    double covered_share = 0.0;  // with a surface (position.w = 1)
    // Share of the covered pixels:
    double outside_share = 0.0;  // on or in front of the near plane, behind the camera, past the far
                                 // plane or not finite (through inverse_view_projection)
    // Of the covered pixels inside the depth range:
    double facing_away_share = 0.0;     // dot(shading normal, eye - position) < 0
    double disagreeing_share = 0.0;     // shading normal > 60 degrees from the geometric normal
    double median_angle_degrees = 0.0;  // between shading and geometric normal
    // The same median with the normals read in the other space (normal_space world: as view-space
    // normals of the camera that inverse_view_projection describes, x right, y up, z backward;
    // view: as world-space normals).
    double other_space_median_angle_degrees = 0.0;
    // The distance between the eye passed and the camera centre of inverse_view_projection, over
    // the median distance of the surfaces from the eye (0 for an orthographic projection).
    double eye_offset = 0.0;
    GbufferAdapterOptions options;  // those checked, to name in the messages

    // Plain-language messages, each naming the likely wrong option; empty when all looks right.
    std::vector<std::string> problems() const;
};

// `options`: those the adapter ran with; `eye`: the camera's world position. Throws Error when
// the three images differ in size or are empty.
GbufferCheck check_gbuffer_conventions(const GbufferReadback& images, const GbufferAdapterOptions& options,
                                       glm::vec3 eye);
// For GiChain: `adapter` (GiChainOptions::adapter) with the frame's matrices and camera position,
// as the chain runs the adapter.
GbufferCheck check_gbuffer_conventions(const GbufferReadback& images, const GbufferAdapterOptions& adapter,
                                       const GiChainFrame& frame);

}  // namespace vplkit::stages
