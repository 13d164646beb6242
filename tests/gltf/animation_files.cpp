#include "animation_files.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace gltf_features {
namespace {

using scene_test::json_float;

template <typename T>
void append(std::vector<uint8_t>& bytes, T value) {
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(T));
}

// `values` as one accessor of `type`, as floats or normalized integers (glTF 2.0 3.11's rounding).
int output_accessor(GltfBuilder& b, const std::vector<float>& values, size_t components, int component_type,
                    const std::string& type) {
    std::vector<uint8_t> bytes;
    for (float v : values) {
        switch (component_type) {
            case scene_test::kByte:
                append(bytes, int8_t(std::lround(v * 127.0f)));
                break;
            case scene_test::kUnsignedByte:
                append(bytes, uint8_t(std::lround(v * 255.0f)));
                break;
            case scene_test::kShort:
                append(bytes, int16_t(std::lround(v * 32767.0f)));
                break;
            case scene_test::kUnsignedShort:
                append(bytes, uint16_t(std::lround(v * 65535.0f)));
                break;
            default:
                append(bytes, v);
        }
    }
    const int view = b.view(bytes.data(), bytes.size());
    return b.accessor(view, component_type, values.size() / components, type,
                      component_type == scene_test::kFloat ? "" : ",\"normalized\":true");
}

}  // namespace

void add_animations(GltfBuilder& b, const std::vector<AnimationKeys>& animations) {
    std::string json = ",\"animations\":[";
    for (size_t a = 0; a < animations.size(); ++a) {
        std::string channels, samplers;
        for (size_t c = 0; c < animations[a].channels.size(); ++c) {
            const ChannelKeys& k = animations[a].channels[c];
            const size_t components = k.path == "rotation" ? 4 : k.path == "weights" ? 1 : 3;
            const std::string type = components == 4 ? "VEC4" : components == 1 ? "SCALAR" : "VEC3";
            const int input = b.accessor(
                b.view(k.times.data(), k.times.size() * sizeof(float)), scene_test::kFloat, k.times.size(), "SCALAR",
                ",\"min\":[" + json_float(k.times.front()) + "],\"max\":[" + json_float(k.times.back()) + "]");
            const int output = output_accessor(b, k.values, components, k.component_type, type);
            channels += std::string(c ? "," : "") + "{\"sampler\":" + std::to_string(c) +
                        ",\"target\":{\"node\":" + std::to_string(k.node) + ",\"path\":\"" + k.path + "\"}}";
            samplers += std::string(c ? "," : "") + "{\"input\":" + std::to_string(input) +
                        ",\"output\":" + std::to_string(output) + ",\"interpolation\":\"" + k.interpolation + "\"}";
        }
        json += std::string(a ? "," : "") + "{";
        if (!animations[a].name.empty()) json += "\"name\":\"" + animations[a].name + "\",";
        json += "\"channels\":[" + channels + "],\"samplers\":[" + samplers + "]}";
    }
    b.top_level_extra += json + "]";
}

GltfBuilder animated_quad(const std::vector<AnimationKeys>& animations) {
    GltfBuilder b;
    b.roots.push_back(b.node("{\"mesh\":" + std::to_string(b.mesh("[" + scene_test::unit_quad(b) + "]")) + "}"));
    b.lights.push_back(R"({"type":"point","color":[1,1,1],"intensity":2})");
    b.roots.push_back(b.node(R"({"translation":[0.5,0.5,1],"extensions":{"KHR_lights_punctual":{"light":0}}})"));
    add_animations(b, animations);
    return b;
}

GltfBuilder animated_scene() {
    ChannelKeys slide{0, "translation", "LINEAR", {0, 2}, {0, 0, 0, 1, 0, 0}};
    ChannelKeys swing{1, "translation", "LINEAR", {0, 2}, {0.5f, 0.5f, 1, 1.5f, 0.5f, 1}};
    return animated_quad({{"slide", {slide}}, {"swing", {swing}}});
}

}  // namespace gltf_features
