#pragma once
// Every subcommand's entry point and usage text; main.cpp lists them in its command table.

#include "cli.hpp"

#include <optional>
#include <string>

namespace vplkit::cli {

int run_info(Args& args);
extern const char* const kInfoUsage;

int run_render(Args& args);
std::string render_usage();

// `vplkit plan`: render's options, the frame's plan printed instead of rendered.
int run_plan(Args& args);
extern const char* const kPlanUsage;

int run_bench(Args& args);
std::string bench_usage();

int run_compare(Args& args);
extern const char* const kCompareUsage;

// `vplkit sequence`: frames along a camera path, optionally with seed 001's temporal metrics.
int run_sequence(Args& args);
extern const char* const kSequenceUsage;

// `vplkit view`: the renderer in a window with a settings panel; --screenshot for scripts.
int run_view(Args& args);
extern const char* const kViewUsage;

// `vplkit bench tree` and `vplkit bench gi --scene NAME` (reached through run_bench; their
// usage is part of bench_usage()).
int run_bench_tree(Args& args);
int run_bench_gi(Args& args, const std::string& scene);
// `vplkit bench direct --scene NAME`: the flat and the tree direct-light samplers, RMSE vs time.
int run_bench_direct(Args& args, const std::string& scene);
// `vplkit bench bvh [--scene NAME]`: the host and the GPU BVH builds, refit, rays per second.
int run_bench_bvh(Args& args, const std::optional<std::string>& scene);

}  // namespace vplkit::cli
