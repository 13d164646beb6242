#pragma once
// `vplkit render --vpls-only`: the VPLs of a frame drawn over it, for a person to check where
// they are. The frame's tonemapped direct light is the grey background at 60% (surfaces in
// shadow faintly shaded by their facing); every VPL the
// camera sees is a dot in its flux's colour (hue only: brightness would hide the dim ones), one
// hidden behind a nearer surface a faint single pixel.

#include "vplkit/renderer.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace vplkit::cli {

struct VplView {
    std::vector<uint8_t> rgba8;  // image.width x image.height, rows top to bottom
    uint32_t visible = 0;        // VPLs drawn as dots
    uint32_t hidden = 0;         // on screen, behind a nearer surface
    uint32_t off_screen = 0;
};

// `image` must come from a render with vpls_only (its vpls and gbuffer_position filled);
// `view_projection` and `eye` are the camera's (vplkit::camera_view for the image's size).
VplView draw_vpl_view(const RenderedImage& image, const glm::mat4& view_projection, glm::vec3 eye);

}  // namespace vplkit::cli
