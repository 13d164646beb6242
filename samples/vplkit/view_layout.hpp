#pragma once
// Where `vplkit view` puts things in its window: the panel docked in a column on the right, the
// frame fitted into the rest, so the panel never covers the image. Without the panel (F1,
// --no-panel) the frame gets the whole window.

#include <vulkan/vulkan.h>

#include <cstdint>

namespace vplkit::cli {

// The panel column's width, in pixels, when the window has room for it.
constexpr uint32_t kPanelColumnWidth = 380;
// The panel's usable height: a default window is at least this tall while the panel shows.
constexpr uint32_t kPanelMinHeight = 480;

struct ViewLayout {
    VkRect2D image_area{};  // the frame is fitted (aspect kept, centred) into this part of the window
    VkRect2D panel_area{};  // empty without the panel
};

// The layout of a window (drawable) of `window` pixels.
ViewLayout view_layout(VkExtent2D window, bool show_panel);

// The window's starting size for a frame of `frame` pixels: the frame at its own size, beside
// the panel's column when the panel shows.
VkExtent2D default_window_size(VkExtent2D frame, bool show_panel);

}  // namespace vplkit::cli
