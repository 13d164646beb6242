#include "pose_scene_file.hpp"

#include <string>

namespace pose_test {

std::filesystem::path write_moving_scene(const std::filesystem::path& dir) {
    using gltf_features::ChannelKeys;
    scene_test::GltfBuilder b;
    b.materials.push_back(R"({"name":"grey","pbrMetallicRoughness":{"baseColorFactor":[0.8,0.8,0.8,1],)"
                          R"("metallicFactor":0,"roughnessFactor":1}})");
    const int quad = b.mesh("[" + scene_test::unit_quad(b, true, true, 0) + "]");
    const std::string mesh = std::to_string(quad);
    b.roots.push_back(b.node(R"({"name":"floor","mesh":)" + mesh + R"(,"translation":[-2,-2,0],"scale":[4,4,1]})"));
    b.roots.push_back(
        b.node(R"({"name":"block","mesh":)" + mesh + R"(,"translation":[-0.75,-0.25,0.6],"scale":[0.5,0.5,1]})"));
    b.lights.push_back(R"({"type":"point","color":[1,1,1],"intensity":4})");
    b.roots.push_back(
        b.node(R"({"name":"lamp","translation":[-0.5,0,2],"extensions":{"KHR_lights_punctual":{"light":0}}})"));
    const ChannelKeys slide{1, "translation", "LINEAR", {0, 2}, {-0.75f, -0.25f, 0.6f, 0.25f, -0.25f, 0.6f}};
    const ChannelKeys swing{2, "translation", "LINEAR", {0, 2}, {-0.5f, 0, 2, 0.5f, 0, 2}};
    gltf_features::add_animations(b, {{"slide", {slide}}, {"swing", {swing}}});
    return b.write(dir, "moving");
}

vplkit::scene::Camera moving_scene_camera() {
    vplkit::scene::Camera camera =
        vplkit::scene::look_at({0.0f, -3.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, 0.9f);
    camera.znear = 0.01f;
    return camera;
}

}  // namespace pose_test
