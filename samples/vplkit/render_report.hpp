#pragma once
// What `vplkit render` prints about frames that did not all run the same work: with --frames > 1
// the first frame makes the VPLs and trees the later ones reuse, so the plan is printed per run of
// frames alike, and the stage table shows the work made on the first frame beside the medians.

#include "vplkit/pass_list.hpp"
#include "vplkit/planner.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace vplkit::cli {

// One line per run of frames with the same plan: "plan: ..." when every frame's is the same; else
// "plan, frame 1: ...", then "plan, frames 2..F: ...; reused from frame 1: brsm vpls, vpl sort".
std::vector<std::string> plan_lines(const std::vector<FramePlan>& plans);

// The GPU time per stage: each stage's median over frames 2..F (every frame when F is 1), then the
// stages only frame 1 ran (the VPLs and trees the later frames reuse) with frame 1's time.
std::string stage_table(const std::vector<std::vector<PassTiming>>& frames, uint32_t width, uint32_t height);

}  // namespace vplkit::cli
