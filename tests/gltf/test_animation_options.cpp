// Which animations a load plays (LoadOptions::time and ::animation), what Scene::animations
// reports, the rest-pose warning, and malformed animations: one error naming the file, the
// animation and the channel.

#include "animation_files.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace {

using gltf_features::ChannelKeys;
using vplkit::scene::LoadOptions;
using vplkit::scene::Scene;

Scene load(const scene_test::GltfBuilder& b, std::optional<double> time, std::optional<std::string> animation = {}) {
    scene_test::TempDir dir("animation_options");
    LoadOptions options;
    options.time = time;
    options.animation = animation;
    return vplkit::scene::load_gltf(b.write(dir.path(), "animated", true), options);
}

float quad_x(const Scene& scene) {
    return scene.vertices.at(0).position.x;
}

float light_x(const Scene& scene) {
    return scene.lights.at(0).position.x;
}

// The error loading `b` gives (with `time` and `animation`), or "" when it loads.
std::string load_error(const scene_test::GltfBuilder& b, std::optional<double> time = 1.0,
                       std::optional<std::string> animation = {}) {
    try {
        load(b, time, animation);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("gltf animation options: no time is the rest pose (warned), Scene::animations gives the spans") {
    const Scene scene = load(gltf_features::animated_scene(), std::nullopt);
    CHECK(quad_x(scene) == 0.0f);
    CHECK(light_x(scene) == 0.5f);
    CHECK_FALSE(scene.time);
    const auto lines = vplkit::scene::warning_lines(scene.warnings);
    REQUIRE(lines.size() == 1);
    CHECK(has(lines[0], "2 animation(s) ignored: no time was given"));
    CHECK(has(lines[0], "set a time to pose the scene"));
    CHECK_FALSE(has(lines[0], "--"));  // runtime messages name settings, not command-line flags
    REQUIRE(scene.animations.size() == 2);
    CHECK(scene.animations[0].name == "slide");
    CHECK(scene.animations[1].name == "swing");
    for (const auto& a : scene.animations) {
        CHECK(a.start == 0.0);
        CHECK(a.end == 2.0);
        CHECK_FALSE(a.applied);
    }
}

TEST_CASE("gltf animation options: every animation plays by default, or one chosen by name or index") {
    const auto b = gltf_features::animated_scene();
    const Scene all = load(b, 1.0);
    CHECK(std::abs(quad_x(all) - 0.5f) <= 1e-6f);
    CHECK(std::abs(light_x(all) - 1.0f) <= 1e-6f);
    CHECK(all.animations[0].applied);
    CHECK(all.animations[1].applied);
    CHECK(vplkit::scene::warning_lines(all.warnings).empty());

    const Scene swing = load(b, 1.0, "swing");
    CHECK(quad_x(swing) == 0.0f);
    CHECK(std::abs(light_x(swing) - 1.0f) <= 1e-6f);
    CHECK_FALSE(swing.animations[0].applied);
    CHECK(swing.animations[1].applied);

    const Scene slide = load(b, 1.0, "0");
    CHECK(std::abs(quad_x(slide) - 0.5f) <= 1e-6f);
    CHECK(light_x(slide) == 0.5f);

    // An animation without a time: posed at its start.
    const Scene start = load(b, std::nullopt, "swing");
    REQUIRE(start.time);
    CHECK(*start.time == 0.0);
    CHECK(light_x(start) == 0.5f);
}

TEST_CASE("gltf animation options: two animations on one property: the later wins, warned (and other warnings)") {
    const ChannelKeys a{0, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0}};
    const ChannelKeys b{0, "translation", "LINEAR", {0, 1}, {0, 0, 0, 3, 0, 0}};
    const Scene scene = load(gltf_features::animated_quad({{"a", {a}}, {"b", {b}}}), 1.0);
    CHECK(quad_x(scene) == 3.0f);
    const auto lines = vplkit::scene::warning_lines(scene.warnings);
    REQUIRE(lines.size() == 1);
    CHECK(has(lines[0], "animation 0 'a' and animation 1 'b' both animate node 0 translation"));
    // A path glTF 2.0 does not define (an extension's): that channel skipped, warned.
    const ChannelKeys pointer{0, "pointer", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0}};
    const Scene skipped = load(gltf_features::animated_quad({{"p", {pointer}}}), 1.0);
    CHECK(quad_x(skipped) == 0.0f);
    REQUIRE(vplkit::scene::warning_lines(skipped.warnings).size() == 1);
    CHECK(has(vplkit::scene::warning_lines(skipped.warnings)[0],
              "animation 0 'p' channel 0 animates path 'pointer', which is not a glTF 2.0 node property: skipped"));
    // A time for a file without animations: the rest pose, said.
    const Scene still = load(gltf_features::animated_quad({}), 1.0);
    REQUIRE(vplkit::scene::warning_lines(still.warnings).size() == 1);
    CHECK(has(vplkit::scene::warning_lines(still.warnings)[0], "the file has no animation"));
}

TEST_CASE("gltf animation options: an animation the file lacks is an error listing those it has") {
    const auto b = gltf_features::animated_scene();
    for (const std::string selector : {"nope", "2", "-1", ""}) {
        CAPTURE(selector);
        const std::string error = load_error(b, 1.0, selector);
        CHECK(has(error, "animated.gltf: animation '" + selector +
                             "' was asked for, but the file has 2 animation(s): "
                             "0 'slide', 1 'swing'"));
    }
    CHECK(has(load_error(gltf_features::animated_quad({}), 1.0, "0"),
              "animation '0' was asked for, but the file has no animation"));
    CHECK(has(load_error(b, std::numeric_limits<double>::quiet_NaN()), "the time to pose the scene at is not finite"));
}

TEST_CASE("gltf animation options: a malformed animation is one error naming file, animation and channel") {
    auto bad = [](ChannelKeys keys) { return gltf_features::animated_quad({{"bad", {keys}}}); };
    const std::string where = "animated.gltf: animation 0 'bad' channel 0";
    const std::string move = where + " (node 0 translation) sampler 0: ";

    std::string error = load_error(bad({0, "translation", "LINEAR", {0, 1, 1}, {0, 0, 0, 1, 0, 0, 2, 0, 0}}));
    CHECK(has(error, move + "input times are not strictly increasing (key 2 at 1 s follows 1 s)"));
    // Checked whether or not the scene is posed: Scene::animations reports every animation's span.
    CHECK(load_error(bad({0, "translation", "LINEAR", {1, 0}, {0, 0, 0, 1, 0, 0}}), std::nullopt) != "");

    error = load_error(bad({0, "translation", "LINEAR", {0, 1, 2}, {0, 0, 0, 1, 0, 0}}));
    CHECK(has(error, move + "3 input key(s) need 3 output element(s), but the output has 2"));
    error = load_error(bad({0, "translation", "CUBICSPLINE", {0, 1}, {0, 0, 0, 1, 0, 0}}));
    CHECK(has(error, move + "2 input key(s) need 6 output element(s) (in-tangent, value, out-tangent per key), but "
                            "the output has 2"));

    error = load_error(bad({9, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0}}));
    CHECK(has(error, where + " refers to node 9, but the file has 2 nodes"));
    error = load_error(bad({0, "translation", "QUADRATIC", {0, 1}, {0, 0, 0, 1, 0, 0}}));
    CHECK(has(error, move + "interpolation 'QUADRATIC' is not LINEAR, STEP or CUBICSPLINE"));
    error = load_error(bad({0, "weights", "LINEAR", {0, 1}, {0, 1}}));
    CHECK(has(error, where + " (node 0 weights) animates morph weights, but the node's mesh has no morph targets"));

    // The same node property twice in one animation.
    const ChannelKeys once{0, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0}};
    error = load_error(gltf_features::animated_quad({{"bad", {once, once}}}));
    CHECK(has(error, "animation 0 'bad' channel 1 (node 0 translation) animates what channel 0 does"));
}
