// warning_lines: LoadWarnings as the sentences the command line prints (scene.hpp).

#include "vplkit/scene.hpp"

#include <set>

namespace vplkit::scene {

std::vector<std::string> warning_lines(const LoadWarnings& warnings) {
    std::vector<std::string> lines;
    std::set<std::string> seen;
    auto add = [&](const std::string& line) {
        if (seen.insert(line).second) lines.push_back(line);
    };
    if (warnings.skipped_primitives) {
        add(std::to_string(warnings.skipped_primitives) +
            " primitive(s) skipped: mode other than TRIANGLES (points, lines, strips, fans)");
    }
    if (warnings.repaired_normals) {
        add(std::to_string(warnings.repaired_normals) +
            " zero-length NORMAL(s) replaced by the adjacent faces' normal");
    }
    if (warnings.untangented_vertices) {
        add(std::to_string(warnings.untangented_vertices) +
            " vertices have no defined tangent (no or degenerate UVs): their normal map is read in an arbitrary "
            "frame");
    }
    for (const std::string& message : warnings.messages) add(message);
    return lines;
}

std::string degenerate_triangles_note(const LoadWarnings& warnings) {
    if (!warnings.degenerate_triangles) return {};
    return std::to_string(warnings.degenerate_triangles) + " zero-area triangle(s) dropped";
}

}  // namespace vplkit::scene
