// The viewer's layout. The column narrows in a small window so the frame keeps some room
// (at least kMinImageWidth pixels, or half the window when even that does not fit).

#include "view_layout.hpp"

#include <algorithm>

namespace vplkit::cli {
namespace {

constexpr uint32_t kMinImageWidth = 64;

}  // namespace

ViewLayout view_layout(VkExtent2D window, bool show_panel) {
    ViewLayout layout;
    uint32_t column = 0;
    if (show_panel) {
        const uint32_t leaving_room = window.width > kMinImageWidth ? window.width - kMinImageWidth : 0;
        column = std::min(kPanelColumnWidth, std::max(window.width / 2, leaving_room));
    }
    layout.image_area = {{0, 0}, {window.width - column, window.height}};
    layout.panel_area = {{int32_t(window.width - column), 0}, {column, column > 0 ? window.height : 0}};
    return layout;
}

VkExtent2D default_window_size(VkExtent2D frame, bool show_panel) {
    if (!show_panel) return frame;
    return {frame.width + kPanelColumnWidth, std::max(frame.height, kPanelMinHeight)};
}

}  // namespace vplkit::cli
