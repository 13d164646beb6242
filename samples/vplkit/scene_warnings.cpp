#include "scene_warnings.hpp"

#include "vplkit/error.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace vplkit::cli {

void report_scene_warnings(const scene::Scene& scene, bool strict) {
    const std::vector<std::string> lines = scene::warning_lines(scene.warnings);
    for (const std::string& line : lines) std::printf("warning: %s\n", line.c_str());
    if (const std::string note = scene::degenerate_triangles_note(scene.warnings); !note.empty()) {
        std::printf("note: %s\n", note.c_str());
    }
    std::fflush(stdout);
    if (strict && !lines.empty()) {
        throw Error("--strict: " + scene.source.string() + " does not render exactly as the file states (" +
                    std::to_string(lines.size()) + " warning" + (lines.size() == 1 ? "" : "s") +
                    "); the first: " + lines.front());
    }
}

}  // namespace vplkit::cli
