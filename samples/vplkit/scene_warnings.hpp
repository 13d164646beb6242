#pragma once
// What render, plan and bench gi tell the user about a scene they loaded: every feature of the
// file the kit skipped or approximated, once per run, and --strict, which makes those an error.

#include "vplkit/scene.hpp"

namespace vplkit::cli {

// Prints "warning: <line>" for each of scene::warning_lines (and "note: " for dropped zero-area
// triangles) to stdout. With `strict`, and at least one warning, throws an Error that names the
// first warning and the count (the caller exits 1 before any device work or output file).
void report_scene_warnings(const scene::Scene& scene, bool strict);

}  // namespace vplkit::cli
