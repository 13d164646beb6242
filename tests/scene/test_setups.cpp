// The standard set-ups file (scenes/setups.txt): it parses, every set-up's scene resolves from any
// working directory (the third-party ones when ../shared is beside the repository), a set-up loads
// with its camera and lights, and malformed set-ups files fail naming file, line and problem.

#include "gltf_builder.hpp"
#include "vplkit/error.hpp"
#include "vplkit/scene_setups.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>

using namespace vplkit::scene;
using namespace scene_test;

namespace {

fs::path setups_file() {
    return fs::path(source_dir()) / "scenes" / "setups.txt";
}

std::string setups_error(const std::string& text) {
    TempDir dir("setups_error");
    write_text(dir / "setups.txt", text);
    try {
        (void)load_setups(dir / "setups.txt");
    } catch (const vplkit::Error& e) {
        return e.what();
    }
    return "";
}

void check_contains(const std::string& message, std::initializer_list<const char*> fragments) {
    INFO("message: " << message);
    REQUIRE(!message.empty());
    for (const char* fragment : fragments) CHECK(message.find(fragment) != std::string::npos);
}

// Changes the working directory for the lifetime of the object.
class WorkingDirectory {
public:
    explicit WorkingDirectory(const fs::path& path) : previous_(fs::current_path()) { fs::current_path(path); }
    ~WorkingDirectory() { fs::current_path(previous_); }

private:
    fs::path previous_;
};

const char* kValid =
    "default = a\n"
    "[a]\n"
    "scene = x.gltf\n"
    "position = 0,0,5\n"
    "target = 0,0,0\n"
    "fov = 40\n"
    "resolution = 64x32\n";

}  // namespace

TEST_CASE("the repository's set-ups file parses and names the standard set-ups") {
    const Setups setups = load_setups(setups_file());
    CHECK(setups.default_name == "cornell");
    CHECK(setups.default_setup().name == "cornell");
    for (const char* name : {"cornell", "cornell-emissive", "many-lights", "cornell-shared", "sponza-sun",
                             "sponza-lite-sun", "breakfast-sun", "glossy"}) {
        INFO(name);
        const Setup& setup = setups.find(name);
        CHECK(setup.scene.is_absolute());
        CHECK(setup.width > 0);
        CHECK(setup.height > 0);
        CHECK(!setup.description.empty());
    }
    const Setup& sponza = setups.find("sponza-sun");
    REQUIRE(sponza.lights.size() == 1);
    CHECK(sponza.lights[0].type == LightType::directional);
    CHECK(sponza.lights[0].origin == LightOrigin::setup);
    CHECK(sponza.lights[0].direction.y < 0.0f);  // the sun shines down
    CHECK(setups.find("breakfast-sun").lights.size() == 1);
    std::string unknown;
    try {
        (void)setups.find("nope");
    } catch (const vplkit::Error& e) {
        unknown = e.what();
    }
    check_contains(unknown, {"no set-up named 'nope'", "cornell-emissive"});
}

TEST_CASE("every set-up's scene resolves from any working directory") {
    TempDir elsewhere("setups_cwd");
    WorkingDirectory cwd(elsewhere.path());
    const Setups setups = load_setups(setups_file());
    const bool have_shared = fs::exists(shared_scenes());
    for (const Setup& setup : setups.setups) {
        INFO(setup.name << ": " << setup.scene.string());
        const bool third_party = setup.scene_as_written.find("shared/scenes") != std::string::npos;
        if (third_party && !have_shared) {
            MESSAGE("skipped " << setup.name << ": " << shared_scenes().string() << " not found");
            CHECK_THROWS_AS(require_scene(setup), vplkit::Error);
            continue;
        }
        CHECK(require_scene(setup) == setup.scene);
        CHECK(fs::is_regular_file(setup.scene));
    }
}

TEST_CASE("a set-up loads with its camera and lights") {
    const Setups setups = load_setups(setups_file());
    const Setup& cornell = setups.find("cornell");
    const Scene s = load_setup_scene(cornell);
    CHECK(s.camera().origin == CameraOrigin::setup);
    CHECK(s.camera().name == "cornell");
    CHECK(s.camera().aspect == 1.0f);
    CHECK(s.camera().position == glm::vec3(0, 1, 3.4f));
    CHECK(s.camera().yfov == doctest::Approx(glm::radians(45.0)));
    CHECK(s.camera().znear > 0.0f);
    CHECK(s.camera().zfar > glm::length(s.bounds.max - s.camera().position));
    CHECK(s.cameras.size() == 2);  // the file's and the set-up's
    CHECK(s.lights.size() == 1);   // the file's point light; the set-up adds none

    // A file camera asked for explicitly wins over the set-up's.
    LoadOptions options;
    options.camera = 0;
    const Scene with_file_camera = load_setup_scene(cornell, options);
    CHECK(with_file_camera.camera().origin == CameraOrigin::file);

    const Setup& breakfast = setups.find("breakfast-sun");
    if (fs::exists(breakfast.scene)) {
        const Scene b = load_setup_scene(breakfast);
        REQUIRE(b.lights.size() == 1);  // the file has none; the set-up's sun
        CHECK(b.lights[0].type == LightType::directional);
        CHECK(b.camera().aspect == doctest::Approx(1280.0 / 720.0));
    } else {
        MESSAGE("skipped breakfast-sun: " << breakfast.scene.string() << " not found");
    }
}

TEST_CASE("a set-up whose scene is missing names the path") {
    TempDir dir("setups_missing_scene");
    write_text(dir / "setups.txt",
               "default = far\n[far]\nscene = ../../elsewhere/shared/scenes/Gone/Gone.gltf\nposition = 0,0,5\n"
               "target = 0,0,0\nfov = 40\nresolution = 64x64\n");
    const Setups setups = load_setups(dir / "setups.txt");
    std::string message;
    try {
        (void)load_setup_scene(setups.find("far"));
    } catch (const vplkit::Error& e) {
        message = e.what();
    }
    const std::string resolved =
        (dir.path() / "../../elsewhere/shared/scenes/Gone/Gone.gltf").lexically_normal().string();
    check_contains(message, {"set-up 'far'", "setups.txt:2", resolved.c_str(), "../shared/scenes", "not found"});
}

TEST_CASE("malformed set-ups files fail with file and line") {
    CHECK(setups_error(kValid).empty());
    check_contains(setups_error(std::string(kValid) + "colour = red\n"), {"setups.txt:8", "unknown key 'colour'"});
    check_contains(setups_error(std::string(kValid) + "fov = 30\n"), {"setups.txt:8", "'fov' given twice"});
    check_contains(setups_error(std::string(kValid) + "sun = 0,-1,0,1,1\n"),
                   {"setups.txt:8", "sun light", "got 5 fields"});
    check_contains(setups_error(std::string(kValid) + "[a]\n"), {"setups.txt:8", "'a' is defined twice"});
    check_contains(setups_error("default = a\n[a]\nscene = x.gltf\n"), {"setups.txt:2", "has no fov line"});
    check_contains(setups_error("[a]\nscene = x.gltf\nposition = 0,0,5\ntarget = 0,0,0\nfov = 40\nresolution = 8x8\n"),
                   {"no 'default = NAME' line"});
    check_contains(
        setups_error(
            "default = b\n[a]\nscene = x.gltf\nposition = 0,0,5\ntarget = 0,0,0\nfov = 40\nresolution = 8x8\n"),
        {"setups.txt:1", "default 'b' names no set-up"});
    std::string bad_vector = kValid;
    bad_vector.replace(bad_vector.find("0,0,5"), 5, "0,0");
    check_contains(setups_error(bad_vector), {"setups.txt:4", "three comma-separated numbers"});
    std::string bad_resolution = kValid;
    bad_resolution.replace(bad_resolution.find("64x32"), 5, "64by32");
    check_contains(setups_error(bad_resolution), {"setups.txt:7", "WIDTHxHEIGHT"});
    std::string same_points = kValid;
    same_points.replace(same_points.find("0,0,0"), 5, "0,0,5");
    check_contains(setups_error(same_points), {"setups.txt:2", "target equals position"});
    check_contains(setups_error("scene = x.gltf\n"), {"setups.txt:1", "outside a [set-up] section"});
}
