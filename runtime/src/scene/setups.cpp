#include "vplkit/error.hpp"
#include "vplkit/scene_setups.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <set>

namespace vplkit::scene {
namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

bool parse_float(std::string_view text, float& out) {
    text = trim(text);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return !text.empty() && ec == std::errc() && end == text.data() + text.size() && std::isfinite(out);
}

struct Parser {
    std::string file;  // for messages
    size_t line = 0;

    [[noreturn]] void fail(const std::string& problem) const {
        throw Error(file + ":" + std::to_string(line) + ": " + problem);
    }

    glm::vec3 vec3(std::string_view key, std::string_view value) const {
        glm::vec3 out;
        size_t start = 0;
        for (int c = 0; c < 3; ++c) {
            const size_t comma = value.find(',', start);
            if ((c < 2) != (comma != std::string_view::npos)) {
                fail(std::string(key) + " = '" + std::string(value) +
                     "': expected three comma-separated numbers X,Y,Z");
            }
            const std::string_view field = value.substr(start, c < 2 ? comma - start : std::string_view::npos);
            if (!parse_float(field, out[c])) {
                fail(std::string(key) + " = '" + std::string(value) + "': '" + std::string(trim(field)) +
                     "' is not a finite number");
            }
            start = comma + 1;
        }
        return out;
    }
};

// Keys a set-up must have; the rest (description, up, sun, point) are optional.
const std::set<std::string> kRequired = {"scene", "position", "target", "fov", "resolution"};
const std::set<std::string> kKnown = {"scene", "description", "position", "target", "up",
                                      "fov",   "resolution",  "sun",      "point"};

void finish(const Parser& parser, const Setup& setup, const std::set<std::string>& seen, size_t header_line) {
    for (const std::string& key : kRequired) {
        if (!seen.count(key)) {
            throw Error(parser.file + ":" + std::to_string(header_line) + ": set-up '" + setup.name + "' has no " +
                        key + " line");
        }
    }
    // The camera must be valid: look_at throws for a degenerate one, named here.
    try {
        (void)look_at(setup.camera.position, setup.camera.target, setup.camera.up,
                      glm::radians(setup.camera.yfov_degrees));
    } catch (const Error& e) {
        throw Error(parser.file + ":" + std::to_string(header_line) + ": set-up '" + setup.name + "': " + e.what());
    }
}

}  // namespace

const Setup& Setups::find(std::string_view name) const {
    for (const Setup& setup : setups) {
        if (setup.name == name) return setup;
    }
    std::string known;
    for (const Setup& setup : setups) known += (known.empty() ? "" : ", ") + setup.name;
    throw Error("no set-up named '" + std::string(name) + "' in " + file.string() + " (known: " + known + ")");
}

Setups load_setups(const std::filesystem::path& path) {
    std::error_code ec;
    const std::filesystem::path file = std::filesystem::absolute(path, ec).lexically_normal();
    std::ifstream in(file);
    if (!in) throw Error(path.string() + ": set-ups file not found or not readable");

    Setups out;
    out.file = file;
    Parser parser{path.string()};
    size_t default_line = 0;
    Setup* current = nullptr;
    std::set<std::string> seen;
    size_t header_line = 0;
    std::set<std::string> names;

    for (std::string raw; std::getline(in, raw);) {
        ++parser.line;
        const std::string_view line = trim(raw);
        if (line.empty() || line.front() == '#') continue;
        if (line.front() == '[') {
            if (line.back() != ']') parser.fail("a set-up header must be [name]");
            const std::string name(trim(line.substr(1, line.size() - 2)));
            if (name.empty() || name.find_first_of(" \t[]=") != std::string::npos) {
                parser.fail("set-up name '" + name + "' must be one word");
            }
            if (!names.insert(name).second) parser.fail("set-up '" + name + "' is defined twice");
            if (current) finish(parser, *current, seen, header_line);
            out.setups.emplace_back();
            current = &out.setups.back();
            current->name = name;
            current->where = parser.file + ":" + std::to_string(parser.line);
            seen.clear();
            header_line = parser.line;
            continue;
        }
        const size_t equals = line.find('=');
        if (equals == std::string_view::npos) parser.fail("expected 'key = value' or '[name]', got '" + raw + "'");
        const std::string key(trim(line.substr(0, equals)));
        const std::string_view value = trim(line.substr(equals + 1));
        if (!current) {
            if (key != "default") parser.fail("'" + key + "' outside a [set-up] section (only 'default' may be)");
            if (!out.default_name.empty()) parser.fail("default is given twice");
            out.default_name = std::string(value);
            default_line = parser.line;
            continue;
        }
        if (!kKnown.count(key)) {
            parser.fail("unknown key '" + key +
                        "' (known: scene, description, position, target, up, fov, resolution, sun, point)");
        }
        if (key != "sun" && key != "point" && !seen.insert(key).second) {
            parser.fail("'" + key + "' given twice in set-up '" + current->name + "'");
        }
        if (key == "scene") {
            if (value.empty()) parser.fail("scene path is empty");
            current->scene_as_written = std::string(value);
            current->scene = (file.parent_path() / std::string(value)).lexically_normal();
        } else if (key == "description") {
            current->description = std::string(value);
        } else if (key == "position") {
            current->camera.position = parser.vec3(key, value);
        } else if (key == "target") {
            current->camera.target = parser.vec3(key, value);
        } else if (key == "up") {
            current->camera.up = parser.vec3(key, value);
        } else if (key == "fov") {
            float fov = 0.0f;
            if (!parse_float(value, fov) || !(fov > 0.0f && fov < 180.0f)) {
                parser.fail("fov = '" + std::string(value) +
                            "': expected a vertical field of view in degrees, in (0, 180)");
            }
            current->camera.yfov_degrees = fov;
        } else if (key == "resolution") {
            const size_t x = value.find('x');
            uint32_t w = 0, h = 0;
            bool ok = x != std::string_view::npos;
            if (ok) {
                const std::string_view ws = trim(value.substr(0, x)), hs = trim(value.substr(x + 1));
                ok = std::from_chars(ws.data(), ws.data() + ws.size(), w).ptr == ws.data() + ws.size() &&
                     std::from_chars(hs.data(), hs.data() + hs.size(), h).ptr == hs.data() + hs.size() && !ws.empty() &&
                     !hs.empty();
            }
            if (!ok || w == 0 || h == 0 || w > 16384 || h > 16384) {
                parser.fail("resolution = '" + std::string(value) + "': expected WIDTHxHEIGHT, each 1..16384");
            }
            current->width = w;
            current->height = h;
        } else {
            try {
                Light light = key == "sun" ? parse_sun(value) : parse_point(value);
                light.origin = LightOrigin::setup;
                light.name = current->name + " " + key;
                current->lights.push_back(std::move(light));
            } catch (const Error& e) {
                parser.fail(e.what());
            }
        }
    }
    if (current) finish(parser, *current, seen, header_line);
    if (out.setups.empty()) throw Error(path.string() + ": no set-up in the file");
    if (out.default_name.empty()) {
        throw Error(path.string() + ": no 'default = NAME' line before the first set-up");
    }
    if (!names.count(out.default_name)) {
        throw Error(path.string() + ":" + std::to_string(default_line) + ": default '" + out.default_name +
                    "' names no set-up in the file");
    }
    return out;
}

const std::filesystem::path& require_scene(const Setup& setup) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(setup.scene, ec)) {
        throw Error("set-up '" + setup.name + "' (" + setup.where + "): scene file " + setup.scene.string() +
                    " not found (written as " + setup.scene_as_written +
                    "; the third-party scenes are expected in ../shared/scenes beside the repository)");
    }
    return setup.scene;
}

Camera setup_camera(const Setup& setup, const Bounds& bounds) {
    Camera camera =
        look_at(setup.camera.position, setup.camera.target, setup.camera.up, glm::radians(setup.camera.yfov_degrees));
    camera.name = setup.name;
    camera.origin = CameraOrigin::setup;
    camera.aspect = float(setup.width) / float(setup.height);
    float farthest = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                          (corner & 4) ? bounds.max.z : bounds.min.z);
        farthest = std::max(farthest, glm::length(p - camera.position));
    }
    const float diagonal = glm::length(bounds.extent());
    camera.zfar = 1.01f * std::max(farthest, diagonal);
    camera.znear = 1e-3f * diagonal;
    return camera;
}

Scene load_setup_scene(const Setup& setup, const LoadOptions& options) {
    Scene scene = load_gltf(require_scene(setup), options);
    scene.lights.insert(scene.lights.end(), setup.lights.begin(), setup.lights.end());
    if (!options.camera) {
        // A file without cameras got a generated one; the set-up's replaces it.
        if (scene.cameras.size() == 1 && scene.cameras[0].origin == CameraOrigin::generated) scene.cameras.clear();
        scene.cameras.push_back(setup_camera(setup, scene.bounds));
        scene.active_camera = uint32_t(scene.cameras.size() - 1);
    }
    return scene;
}

}  // namespace vplkit::scene
