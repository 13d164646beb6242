#pragma once
// Every subcommand's declaration: add_<name> declares it on the vplkit app (its options, each
// with its help and its check) and appends what runs it; main.cpp lists them.

#include "cli.hpp"
#include "cli_app.hpp"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace vplkit::cli {

void add_info(CLI::App& vplkit, Runners& runners);
// render, and plan (render's options, the frame's plan printed instead of rendered).
void add_render(CLI::App& vplkit, Runners& runners);
void add_plan(CLI::App& vplkit, Runners& runners);
// bench and its benchmarks: sort, tree, bvh, gi, direct (bench without a name: gi).
void add_bench(CLI::App& vplkit, Runners& runners);
void add_compare(CLI::App& vplkit, Runners& runners);
// sequence: frames along a camera path, optionally with the temporal error metrics.
void add_sequence(CLI::App& vplkit, Runners& runners);

// view: the renderer in a window with a settings panel (render's options); --screenshot for scripts.
void add_view(CLI::App& vplkit, Runners& runners);

// bench's benchmarks (cmd_bench_<name>.cpp), declared on the bench command by add_bench.
void add_bench_tree(CLI::App& bench, Runners& runners);
void add_bench_bvh(CLI::App& bench, Runners& runners);
void add_bench_gi(CLI::App& bench, Runners& runners);
void add_bench_direct(CLI::App& bench, Runners& runners);

}  // namespace vplkit::cli
