// The viewer's panel. A setting is changed on a copy and kept only when validate_gi_settings
// accepts it, so the renderer never sees a combination the command line would refuse.

#include "view_panel.hpp"

#include "setting_flags.hpp"

#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/stages/smc.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <sstream>

namespace vplkit::cli {
namespace {

constexpr size_t kHistory = 120;  // frames in the time graphs

// A combo box over `names`; true when the choice changed.
bool choose(const char* label, int& index, const std::vector<std::string>& names) {
    bool changed = false;
    if (ImGui::BeginCombo(label, names[size_t(index)].c_str())) {
        for (int i = 0; i < int(names.size()); ++i) {
            if (ImGui::Selectable(names[size_t(i)].c_str(), i == index) && i != index) {
                index = i;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

// A whole-number slider on a logarithmic scale (VPL counts span orders of magnitude).
bool slide_count(const char* label, uint32_t& value, int low, int high) {
    int v = int(value);
    if (!ImGui::SliderInt(label, &v, low, high, "%d", ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp))
        return false;
    value = uint32_t(std::clamp(v, low, high));
    return true;
}

}  // namespace

bool ViewPanel::draw(RenderSettings& settings, const RenderedImage& last, const PanelColumn& column) {
    // Docked beside the frame, not over it: placed and sized every frame (a resized window
    // moves it), opaque, not movable; a fixed size also shows it in a one-frame screenshot (an
    // auto-sized window stays hidden in its first frame).
    ImGui::SetNextWindowPos(ImVec2(column.x, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(column.width, column.height), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(1.0f);
    const ImGuiWindowFlags docked = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;
    bool changed = false;
    if (ImGui::Begin("vplkit", nullptr, docked)) {
        // The widgets leave room on their right for the longest label.
        ImGui::PushItemWidth(-ImGui::CalcTextSize("VPLs (smc budget)").x - ImGui::GetStyle().ItemInnerSpacing.x);
        // frame: how many frames this view and these settings have accumulated, this one included.
        ImGui::Text("%ux%u, %u VPLs, frame %u, exposure %.2f", last.width, last.height, last.vpl_count,
                    settings.frame + 1, double(last.exposure));
        // The cameras and keys, where a user looks for them (view --help says the same).
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        ImGui::TextWrapped(
            "orbit: left-drag, wheel; fly: right-drag, W A S D, Q E (Shift faster); F12 screenshot, "
            "F1 panel");
        ImGui::PopStyleColor();
        if (!budget_.empty()) ImGui::TextWrapped("%s", budget_.c_str());
        RenderSettings edited = settings;
        if (draw_settings(edited, last.plan)) {
            try {
                validate_gi_settings(edited);
                settings = edited;
                error_.clear();
                changed = true;
            } catch (const Error& e) {
                error_ = with_flags(e.what());
            }
        }
        if (!error_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "%s", error_.c_str());
        draw_exact_error();
        if (ImGui::CollapsingHeader("plan")) {
            std::istringstream lines(with_flags(last.plan.describe()));
            for (std::string line; std::getline(lines, line);) ImGui::TextWrapped("%s", line.c_str());
        }
        if (ImGui::CollapsingHeader("GPU time per stage", ImGuiTreeNodeFlags_DefaultOpen)) draw_times(last);
        ImGui::PopItemWidth();
    }
    ImGui::End();
    return changed;
}

bool ViewPanel::draw_settings(RenderSettings& s, const FramePlan& plan) {
    bool changed = false;
    std::vector<std::string> methods;
    for (const GiMethodInfo& m : gi_methods()) methods.emplace_back(m.name);
    int method = int(s.method);
    if (choose("method", method, methods)) s.method = GiMethod(method), changed = true;
    const GiMethodInfo& info = gi_method(s.method);

    if (info.samples) {
        int spp = int(s.samples_per_pixel);
        if (ImGui::SliderInt("spp", &spp, 1, 64, "%d", ImGuiSliderFlags_AlwaysClamp)) {
            s.samples_per_pixel = uint32_t(spp), changed = true;
        }
        int glossy = int(s.glossy_branch);
        if (choose("glossy lobe", glossy, {"auto", "on", "off"}))
            s.glossy_branch = GlossyBranch(glossy), changed = true;
    }
    if (s.method != GiMethod::none) {
        int half = s.half_resolution_gi ? 1 : 0;
        if (choose("GI resolution", half, {"full", "half"})) s.half_resolution_gi = half == 1, changed = true;
    }
    if (s.method != GiMethod::none && !info.ground_truth) {
        int denoise = int(s.denoise);
        if (choose("denoise", denoise, {"off", "temporal", "svgf"})) s.denoise = DenoiseMode(denoise), changed = true;
    }
    if (info.vpls == GiVpls::source) {
        // The enum's order is ir, brsm, smc, automatic; the list shows auto first.
        const VplSource order[] = {VplSource::automatic, VplSource::ir, VplSource::brsm, VplSource::smc};
        int source = int(std::find(std::begin(order), std::end(order), s.vpl_source) - std::begin(order));
        if (choose("VPL source", source, {"auto", "ir", "brsm", "smc"})) s.vpl_source = order[source], changed = true;
        // The count the resolved source reads.
        const VplSource resolved = s.vpl_source == VplSource::automatic ? plan.vpl_source : s.vpl_source;
        if (resolved == VplSource::brsm) {
            changed |= slide_count("VPLs (brsm)", s.brsm.vpl_count, 16, 1 << 16);
        } else if (resolved == VplSource::smc) {
            changed |= slide_count("VPLs (smc budget)", s.smc.budget, 16, int(stages::kSmcMaxBudget));
        } else {
            changed |= slide_count("light paths (ir)", s.vpl_paths, 16, 1 << 18);
        }
    }
    changed |= ImGui::Checkbox("anti-aliasing (still camera)", &s.antialias);
    changed |= ImGui::Checkbox("automatic exposure", &s.auto_exposure);
    if (!s.auto_exposure) {
        changed |= ImGui::SliderFloat("exposure", &s.exposure, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        s.exposure = std::max(s.exposure, 0.05f);
    }
    return changed;
}

void ViewPanel::draw_exact_error() {
    if (ImGui::Button("compare with exact")) exact_requested_ = true;
    ImGui::SameLine();
    if (exact_error_) {
        ImGui::Text("relative RMSE %.4f (pixel centres)", *exact_error_);
    } else {
        ImGui::TextDisabled("(renders every VPL once: slow)");
    }
}

void ViewPanel::draw_times(const RenderedImage& last) {
    if (total_ms_.empty()) {
        ImGui::TextUnformatted("(no frame yet)");
        return;
    }
    const std::vector<float> totals(total_ms_.begin(), total_ms_.end());
    char label[96];
    std::snprintf(label, sizeof label, "total %.2f ms", double(totals.back()));
    ImGui::PlotLines("##total", totals.data(), int(totals.size()), 0, label, 0.0f, FLT_MAX, ImVec2(0, 48));
    for (const auto& [name, history] : stage_ms_) {
        if (history.empty()) continue;
        const std::vector<float> values(history.begin(), history.end());
        std::snprintf(label, sizeof label, "%.3f ms", double(values.back()));
        ImGui::PlotLines(("##" + name).c_str(), values.data(), int(values.size()), 0, label, 0.0f, FLT_MAX,
                         ImVec2(160, 24));
        ImGui::SameLine();
        ImGui::TextUnformatted(name.c_str());
    }
    if (last.exact_gi_wall_ms > 0.0) ImGui::Text("exact gi (host wall clock): %.1f ms", last.exact_gi_wall_ms);
}

void ViewPanel::add_frame(const RenderedImage& image) {
    // Passes summed by the stage that owns them (a stage records several passes).
    std::vector<std::pair<std::string, float>> frame;
    for (const PassTiming& t : image.timings) {
        const std::string name = t.tag ? stage_name(FrameStage(t.tag - 1)) : t.name;
        auto it = std::find_if(frame.begin(), frame.end(), [&](const auto& s) { return s.first == name; });
        if (it == frame.end()) it = frame.insert(frame.end(), {name, 0.0f});
        it->second += float(t.gpu_ms);
    }
    float total = 0.0f;
    for (auto& [name, history] : stage_ms_) {
        auto it = std::find_if(frame.begin(), frame.end(), [&](const auto& s) { return s.first == name; });
        history.push_back(it == frame.end() ? 0.0f : it->second);  // a stage left out this frame took 0
        if (history.size() > kHistory) history.pop_front();
    }
    for (const auto& [name, ms] : frame) {
        total += ms;
        auto known = std::find_if(stage_ms_.begin(), stage_ms_.end(), [&](const auto& s) { return s.first == name; });
        if (known == stage_ms_.end()) stage_ms_.push_back({name, std::deque<float>(1, ms)});
    }
    total_ms_.push_back(total);
    if (total_ms_.size() > kHistory) total_ms_.pop_front();
}

}  // namespace vplkit::cli
