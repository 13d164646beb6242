#pragma once
// What `--stats FILE.json` holds for `vplkit render` and `vplkit sequence`, piece by piece: the
// device, the plans (every stage kept or left out, with the reason), the GPU times, the frame's
// counters. The commands put the pieces together and write them (stats_json.hpp); every number
// that can fail to be finite goes through json_number (null then).

#include "vplkit/device_info.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vplkit::cli {

// Format and meaning of null, the first keys of every stats file.
nlohmann::ordered_json stats_header(const std::string& command);

// name, type, driver, driver_info, api_version, lavapipe (true on Mesa's CPU device), reason.
nlohmann::ordered_json device_stats(const DeviceInfo& device);

// Frames are named by index from 0 (sequence's frame_0000.png is index 0; render's first frame,
// the one that pays for shader compiles, too).
//
// Records each frame's plan and keeps one entry per run of frames with the same plan:
// [{"frame_indices": [first, last], "summary", "stages": [{"stage", "runs", "reason"}], ...}].
// A reused VPL set changes the plan, so the first frame's entry differs from the rest's.
class PlanLog {
public:
    void add(uint32_t frame_index, const FramePlan& plan);
    const nlohmann::ordered_json& json() const { return plans_; }

private:
    nlohmann::ordered_json plans_ = nlohmann::ordered_json::array();
    std::string last_;  // the last plan's describe()
};

// GPU times from each frame's passes. With more than one frame the first is left out (it pays
// for shader compiles, as render's table does). Keys: frame_ms (the median of the timed frames'
// sums over every pass), timed_frame_indices [first, last], frame_gpu_ms (every frame's sum),
// stage_ms (each planner stage's median over the timed frames that ran it, by the passes' tags:
// also the VPLs' cost), pass_ms (each pass name's median and its passes per frame, as render's
// table prints them), first_frame_only_stage_ms and first_frame_only_pass_ms (what only the
// untimed first frame ran, e.g. the VPLs and trees later frames reuse, with its time; render's
// "made on frame 1 only" lines).
nlohmann::ordered_json timing_stats(const std::vector<std::vector<PassTiming>>& frames);

// The frame's counters, those render prints: VPLs, reuse, the sampling methods' traversal
// counts, the direct-light tree's, SMC's, upsampling's, dropped and non-finite pixels.
nlohmann::ordered_json counters_stats(const RenderedImage& image, const RenderSettings& settings);

}  // namespace vplkit::cli
