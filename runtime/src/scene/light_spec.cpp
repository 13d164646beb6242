#include "vplkit/error.hpp"
#include "vplkit/scene_lights.hpp"

#include <glm/geometric.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>
#include <vector>

namespace vplkit::scene {
namespace {

constexpr size_t kFields = 7;

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

// Splits on ',' and parses each field as a finite float. `kind` ("sun") and `syntax`
// ("DX,DY,DZ,R,G,B,INTENSITY") make every message self-contained.
std::array<float, kFields> parse_fields(std::string_view spec, const char* kind, const char* syntax) {
    const std::string quoted = std::string(kind) + " light '" + std::string(spec) + "': ";
    std::vector<std::string_view> fields;
    size_t start = 0;
    while (true) {
        const size_t comma = spec.find(',', start);
        fields.push_back(
            trim(spec.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    if (fields.size() != kFields) {
        throw Error(quoted + "expected " + std::to_string(kFields) + " comma-separated numbers " + syntax + ", got " +
                    std::to_string(fields.size()) + " field" + (fields.size() == 1 ? "" : "s"));
    }
    std::array<float, kFields> values{};
    // The field names in order, taken from the syntax string, for messages like "G is not a number".
    std::vector<std::string> names;
    for (std::string_view rest = syntax;;) {
        const size_t comma = rest.find(',');
        names.emplace_back(rest.substr(0, comma));
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
    }
    for (size_t i = 0; i < kFields; ++i) {
        std::string_view text = fields[i];
        if (!text.empty() && text.front() == '+') text.remove_prefix(1);  // from_chars rejects '+'
        float value = 0.0f;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (ec == std::errc::result_out_of_range && end == text.data() + text.size()) {
            throw Error(quoted + names[i] + " (" + std::string(fields[i]) + ") is out of the float range");
        }
        if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
            throw Error(quoted + names[i] + " ('" + std::string(fields[i]) + "') is not a number");
        }
        if (!std::isfinite(value)) {
            throw Error(quoted + names[i] + " is " + std::string(fields[i]) + ": every value must be finite");
        }
        values[i] = value;
    }
    for (size_t i = 3; i < 6; ++i) {
        if (values[i] < 0.0f) throw Error(quoted + "colour component " + names[i] + " is negative");
    }
    if (values[6] < 0.0f) throw Error(quoted + "intensity is negative");
    return values;
}

}  // namespace

Light parse_sun(std::string_view spec) {
    const auto v = parse_fields(spec, "sun", "DX,DY,DZ,R,G,B,INTENSITY");
    const glm::dvec3 direction(v[0], v[1], v[2]);
    const double length = glm::length(direction);
    // A direction too short to normalize in float is as meaningless as a zero one.
    if (!(length > 1e-30)) {
        throw Error("sun light '" + std::string(spec) + "': direction DX,DY,DZ is zero");
    }
    Light light;
    light.type = LightType::directional;
    light.origin = LightOrigin::command_line;
    light.name = "sun";
    light.direction = glm::vec3(direction / length);
    light.color = {v[3], v[4], v[5]};
    light.intensity = v[6];
    return light;
}

Light parse_point(std::string_view spec) {
    const auto v = parse_fields(spec, "point", "X,Y,Z,R,G,B,INTENSITY");
    Light light;
    light.type = LightType::point;
    light.origin = LightOrigin::command_line;
    light.name = "point";
    light.position = {v[0], v[1], v[2]};
    light.color = {v[3], v[4], v[5]};
    light.intensity = v[6];
    return light;
}

}  // namespace vplkit::scene
