// The --sun / --point light syntax: values as written (direction normalized), and one clear
// error for each kind of malformed input, quoting the input.

#include "vplkit/error.hpp"
#include "vplkit/scene_lights.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <string>

using namespace vplkit::scene;

namespace {

std::string sun_error(const std::string& spec) {
    try {
        (void)parse_sun(spec);
    } catch (const vplkit::Error& e) {
        return e.what();
    }
    return "";
}

std::string point_error(const std::string& spec) {
    try {
        (void)parse_point(spec);
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

}  // namespace

TEST_CASE("sun and point specs parse") {
    const Light sun = parse_sun("0,-3,4,1,0.9,0.8,2.5");
    CHECK(sun.type == LightType::directional);
    CHECK(sun.origin == LightOrigin::command_line);
    CHECK(sun.direction.x == 0.0f);
    CHECK(sun.direction.y == doctest::Approx(-0.6).epsilon(1e-7));
    CHECK(sun.direction.z == doctest::Approx(0.8).epsilon(1e-7));
    CHECK(sun.color == glm::vec3(1.0f, 0.9f, 0.8f));
    CHECK(sun.intensity == 2.5f);

    const Light point = parse_point(" 1.5 , +2 ,-3e-1, 1,1,1, 0 ");  // spaces, '+', exponents, zero intensity
    CHECK(point.type == LightType::point);
    CHECK(point.origin == LightOrigin::command_line);
    CHECK(point.position == glm::vec3(1.5f, 2.0f, -0.3f));
    CHECK(point.color == glm::vec3(1.0f));
    CHECK(point.intensity == 0.0f);
}

TEST_CASE("malformed light specs are rejected with the reason") {
    check_contains(sun_error("0,-1,0,1,1,1"), {"sun light '0,-1,0,1,1,1'", "expected 7", "got 6 fields"});
    check_contains(sun_error("0,-1,0,1,1,1,1,1"), {"got 8 fields"});
    check_contains(sun_error(""), {"got 1 field"});
    check_contains(point_error("1,2,three,1,1,1,1"), {"point light", "Z ('three') is not a number"});
    check_contains(point_error("1,2,3,1,1,1,"), {"INTENSITY ('') is not a number"});
    check_contains(point_error("1,2,3,1..5,1,1,1"), {"R ('1..5') is not a number"});
    check_contains(sun_error("0,-1,0,1,nan,1,1"), {"G is nan", "finite"});
    check_contains(sun_error("0,-1,0,1,1,1,inf"), {"INTENSITY is inf", "finite"});
    check_contains(point_error("1e99,0,0,1,1,1,1"), {"X (1e99) is out of the float range"});
    check_contains(sun_error("0,0,0,1,1,1,1"), {"direction DX,DY,DZ is zero"});
    check_contains(sun_error("0,-1,0,1,1,1,-2"), {"intensity is negative"});
    check_contains(point_error("0,1,0,1,-0.5,1,2"), {"colour component G is negative"});
}
