// What vplkit still skips is said once per thing: feature_files' skipped_features (a POINTS
// primitive, an animation, an unsupported extension the file only uses) gives exactly three
// warning lines, each naming what was skipped. (tests/cli checks that render, plan and bench gi
// print them once and that --strict fails on them.)

#include "feature_files.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>

TEST_CASE("gltf: each skipped feature is named in exactly one warning line") {
    scene_test::TempDir dir("skipped");
    const auto scene = vplkit::scene::load_gltf(gltf_features::skipped_features().write(dir.path(), "skipped", true));
    const auto lines = vplkit::scene::warning_lines(scene.warnings);
    REQUIRE(lines.size() == 3);
    CHECK(lines[0].find("primitive(s) skipped: mode other than TRIANGLES") != std::string::npos);
    int animation = 0, extension = 0;
    for (const std::string& line : lines) {
        animation += line.find("animation") != std::string::npos;
        extension += line.find("KHR_materials_clearcoat") != std::string::npos;
    }
    CHECK(animation == 1);
    CHECK(extension == 1);
}
