#include "camera_path.hpp"

#include "vplkit/error.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace vplkit::cli {

std::vector<CameraKey> read_camera_keys(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw Error(file.string() + ": cannot read the keyframe file");
    std::vector<CameraKey> keys;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream words(line);
        std::vector<double> v;
        double x = 0.0;
        while (words >> x) v.push_back(x);
        const std::string where = file.string() + ":" + std::to_string(number) + ": ";
        if (!words.eof()) throw Error(where + "not a number");
        if (v.empty()) continue;
        if (v.size() != 7)
            throw Error(where + "expected TIME PX PY PZ TX TY TZ (7 numbers), got " + std::to_string(v.size()));
        for (double value : v) {
            if (!std::isfinite(value)) throw Error(where + "a number is not finite");
        }
        CameraKey key{v[0], glm::vec3(v[1], v[2], v[3]), glm::vec3(v[4], v[5], v[6])};
        if (!keys.empty() && !(key.time > keys.back().time)) throw Error(where + "times must increase");
        if (key.position == key.target) throw Error(where + "the position equals the target");
        keys.push_back(key);
    }
    if (keys.size() < 2) throw Error(file.string() + ": a camera path needs at least two keys");
    return keys;
}

namespace {

scene::Camera looking(const scene::Camera& base, glm::vec3 position, glm::vec3 target, glm::vec3 up) {
    scene::Camera c = scene::look_at(position, target, up, base.yfov);
    c.aspect = base.aspect;
    c.znear = base.znear;
    c.zfar = base.zfar;
    c.name = base.name;
    return c;
}

}  // namespace

std::vector<scene::Camera> keyframe_path(const std::vector<CameraKey>& keys, const scene::Camera& base, uint32_t n) {
    std::vector<scene::Camera> path;
    const double t0 = keys.front().time, t1 = keys.back().time;
    for (uint32_t i = 0; i < n; ++i) {
        const double t = n > 1 ? t0 + (t1 - t0) * double(i) / double(n - 1) : t0;
        size_t k = 0;
        while (k + 2 < keys.size() && keys[k + 1].time <= t) ++k;
        const CameraKey& a = keys[k];
        const CameraKey& b = keys[k + 1];
        const float f = float(std::clamp((t - a.time) / (b.time - a.time), 0.0, 1.0));
        path.push_back(
            looking(base, glm::mix(a.position, b.position, f), glm::mix(a.target, b.target, f), {0.0f, 1.0f, 0.0f}));
    }
    return path;
}

std::vector<scene::Camera> orbit_path(const scene::Camera& base, glm::vec3 target, float degrees, uint32_t n,
                                      glm::vec3 up) {
    std::vector<scene::Camera> path;
    const glm::vec3 axis = glm::normalize(up);
    const glm::vec3 d = base.position - target;
    // d's part along the axis stays; the rest turns about it (Rodrigues). With +Y up:
    // (d.x cos a + d.z sin a, d.y, d.z cos a - d.x sin a).
    const glm::vec3 along = axis * glm::dot(axis, d);
    const glm::vec3 across = d - along;
    const glm::vec3 side = glm::cross(axis, d);
    for (uint32_t i = 0; i < n; ++i) {
        const float a = glm::radians(n > 1 ? degrees * float(i) / float(n - 1) : 0.0f);
        const glm::vec3 turned = along + across * std::cos(a) + side * std::sin(a);
        path.push_back(looking(base, target + turned, target, axis));
    }
    return path;
}

}  // namespace vplkit::cli
