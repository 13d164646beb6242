#pragma once
// The viewer's panel (Dear ImGui): the method and its main settings, the VPL source and count,
// the glossy lobe, the exposure; the planner's plan with its reasons; each stage's GPU time over
// the last frames as a graph. Changing a setting re-plans the frame (the renderer decides
// what to rebuild from the plan's keys).

#include "vplkit/planner.hpp"
#include "vplkit/render_settings.hpp"

#include <deque>
#include <string>
#include <utility>
#include <vector>

namespace vplkit {
struct RenderedImage;
namespace scene {
struct Scene;
}
}  // namespace vplkit

namespace vplkit::cli {

class ViewPanel {
public:
    explicit ViewPanel(const scene::Scene& scene);

    // Draws the panel (between Gui::begin_frame and record) for the frame `last`. Returns true
    // when it changed `settings` (only to settings validate_gi_settings accepts).
    bool draw(RenderSettings& settings, const RenderedImage& last);
    // Adds a rendered frame's stage times to the graphs.
    void add_frame(const RenderedImage& image);
    // Shows a message under the settings (e.g. why the renderer refused them) until they change.
    void set_error(std::string message) { error_ = std::move(message); }

private:
    void update_plan(const RenderSettings& settings);
    bool draw_settings(RenderSettings& settings);
    void draw_plan(const RenderSettings& settings);
    void draw_times(const RenderedImage& last);

    const scene::Scene& scene_;
    std::string error_;
    // The plan of the settings it was made for (planning is pure, but not free on a big scene).
    std::string planned_key_;
    FramePlan plan_;
    // Each stage's GPU milliseconds over the last frames, stages in the order first seen.
    std::vector<std::pair<std::string, std::deque<float>>> stage_ms_;
    std::deque<float> total_ms_;
};

}  // namespace vplkit::cli
