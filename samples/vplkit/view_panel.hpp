#pragma once
// The viewer's panel (Dear ImGui): the method and its main settings, the VPL source and count,
// the glossy lobe, the exposure; the last frame's plan with the planner's reasons; the error
// against an exact frame on request; each stage's GPU time over the last frames as a graph.
// Changing a setting re-plans the next frame (the renderer decides what to rebuild from the
// plan's keys).

#include "vplkit/planner.hpp"
#include "vplkit/render_settings.hpp"

#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vplkit {
struct RenderedImage;
}

namespace vplkit::cli {

// Where the panel goes, in ImGui's coordinates (the window's points): a column x..x+width, the
// window's height; it scrolls when its contents are taller.
struct PanelColumn {
    float x = 0.0f, width = 0.0f, height = 0.0f;
};

class ViewPanel {
public:
    // Draws the panel (between Gui::begin_frame and record) for the frame `last`, filling
    // `column`. Returns true when it changed `settings` (only to settings validate_gi_settings
    // accepts).
    bool draw(RenderSettings& settings, const RenderedImage& last, const PanelColumn& column);
    // Adds a rendered frame's stage times to the graphs.
    void add_frame(const RenderedImage& image);
    // Shows a message under the settings (e.g. why the renderer refused them) until they change.
    void set_error(std::string message) { error_ = std::move(message); }

    // The budget's choice (`vplkit view --budget-ms`), shown above the settings.
    void set_budget(std::string line) { budget_ = std::move(line); }

    // "compare with exact" was pressed since the last call.
    bool take_exact_request() { return std::exchange(exact_requested_, false); }
    // The frame's relative RMSE against the exact frame of the same view and VPLs; none: no
    // such frame (the view or the settings changed since).
    void set_exact_error(std::optional<double> error) { exact_error_ = error; }

private:
    bool draw_settings(RenderSettings& settings, const FramePlan& plan);
    void draw_exact_error();
    void draw_times(const RenderedImage& last);

    std::string error_;
    std::string budget_;
    bool exact_requested_ = false;
    std::optional<double> exact_error_;
    // Each stage's GPU milliseconds over the last frames, stages in the order first seen.
    std::vector<std::pair<std::string, std::deque<float>>> stage_ms_;
    std::deque<float> total_ms_;
};

}  // namespace vplkit::cli
