#pragma once
// Punctual lights (KHR_lights_punctual semantics) and the command-line light syntax shared by the
// vplkit command line, the standard set-ups file and the tests:
//   --sun   DX,DY,DZ,R,G,B,INTENSITY   directional light travelling along (DX,DY,DZ), in lux
//   --point X,Y,Z,R,G,B,INTENSITY      point light at (X,Y,Z), in candela
// Units are those of KHR_lights_punctual: a renderer that works in radiometric units reads lux as
// W/m^2 and candela as W/sr, scaled by the same factor for every light.

#include <glm/vec3.hpp>

#include <cstdint>
#include <numbers>
#include <string>
#include <string_view>

namespace vplkit::scene {

enum class LightType : uint32_t { directional, point, spot };

// Where a light came from, so a tool can say which lights the file brought and which were added.
enum class LightOrigin : uint32_t { file, command_line, setup };

struct Light {
    LightType type = LightType::point;
    LightOrigin origin = LightOrigin::file;
    std::string name;
    glm::vec3 color{1.0f};     // linear RGB, each component >= 0
    float intensity = 1.0f;    // directional: lux (lm/m^2); point and spot: candela (lm/sr); >= 0
    glm::vec3 position{0.0f};  // world space; point and spot lights
    // World space, unit length: the direction the light travels (from the light into the scene;
    // a node's -Z axis in KHR_lights_punctual). Directional and spot lights.
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    float range = 0.0f;  // distance beyond which a point or spot light is cut off; 0 = unlimited
    // Spot lights: full intensity inside the inner angle, zero outside the outer (radians from the
    // axis, 0 <= inner < outer <= pi/2; the defaults are KHR_lights_punctual's).
    float inner_cone_angle = 0.0f;
    float outer_cone_angle = std::numbers::pi_v<float> / 4.0f;
};

// "DX,DY,DZ,R,G,B,INTENSITY" -> a directional light (direction normalized, origin command_line).
// Throws vplkit::Error quoting `spec` and naming the problem: not seven fields, a field that is
// not a number, a NaN or infinite value, a zero direction, a negative colour or intensity.
Light parse_sun(std::string_view spec);

// "X,Y,Z,R,G,B,INTENSITY" -> a point light (origin command_line); errors as parse_sun.
Light parse_point(std::string_view spec);

}  // namespace vplkit::scene
