#pragma once
// One point of `vplkit bench gi` measured: rendered F frames (the first untimed when F > 1: shader
// compiles at first dispatch), each pass's GPU time, the frame's error against the ground truth,
// and its image. The sweeps' points and the budget chooser's choices (bench_gi_budget.hpp) alike.

#include "bench_gi.hpp"

#include "vplkit/render_settings.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace vplkit {
class Renderer;
namespace scene {
struct Camera;
}
}  // namespace vplkit

namespace vplkit::cli {

// Renders `p` with `s` and fills its times, metrics and image (written under `out`). False, with
// `failure` the device's reason and p.frames 0, for a point the device could not run.
bool measure_bench_point(Renderer& renderer, const scene::Camera& camera, RenderSettings s, uint32_t frames,
                         const std::vector<float>& truth_rgb, const std::vector<float>& truth_radiance,
                         const std::filesystem::path& out, BenchPoint& p, std::string& failure);

}  // namespace vplkit::cli
