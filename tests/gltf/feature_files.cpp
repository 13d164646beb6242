#include "feature_files.hpp"

#include <glm/vec4.hpp>

#include <cstring>

namespace gltf_features {
namespace {

using scene_test::kFloat;
using scene_test::kUnsignedByte;
using scene_test::kUnsignedShort;

// A point light 1 above the unit quad's centre, on node `node` of `b` (appended to the roots).
void add_light(GltfBuilder& b) {
    b.lights.push_back(R"({"type":"point","color":[1,1,1],"intensity":2})");
    b.roots.push_back(b.node(R"({"translation":[0.5,0.5,1],"extensions":{"KHR_lights_punctual":{"light":0}}})"));
}

// `values` (count x components floats in [0, 1]) as `component_type`, normalized when an integer.
int normalized_accessor(GltfBuilder& b, const std::vector<float>& values, size_t components, int component_type,
                        const std::string& type) {
    std::vector<uint8_t> bytes;
    for (float v : values) {
        if (component_type == kFloat) {
            const auto* p = reinterpret_cast<const uint8_t*>(&v);
            bytes.insert(bytes.end(), p, p + 4);
        } else if (component_type == kUnsignedByte) {
            bytes.push_back(uint8_t(v * 255.0f + 0.5f));
        } else {
            const uint16_t s = uint16_t(v * 65535.0f + 0.5f);
            const auto* p = reinterpret_cast<const uint8_t*>(&s);
            bytes.insert(bytes.end(), p, p + 2);
        }
    }
    // Vertex attributes start on 4-byte element boundaries (glTF 2.0 3.6.2.4): pad each element.
    const size_t size = component_type == kFloat ? 4 : component_type == kUnsignedByte ? 1 : 2;
    const size_t element = components * size;
    const size_t stride = (element + 3) / 4 * 4;
    std::vector<uint8_t> strided;
    const size_t count = values.size() / components;
    for (size_t i = 0; i < count; ++i) {
        strided.insert(strided.end(), bytes.begin() + long(i * element), bytes.begin() + long((i + 1) * element));
        strided.resize((i + 1) * stride, 0);
    }
    const int view = b.view(strided.data(), strided.size(), stride == element ? 0 : stride);
    return b.accessor(view, component_type, count, type, component_type == kFloat ? "" : ",\"normalized\":true");
}

}  // namespace

GltfBuilder vertex_colors(int component_type, bool rgba) {
    GltfBuilder b;
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int n = b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int i = b.indices({0, 1, 2, 0, 2, 3});
    const std::vector<glm::vec4> corners = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    std::vector<float> values;
    for (const glm::vec4& c : corners) {
        for (int k = 0; k < (rgba ? 4 : 3); ++k) values.push_back(c[k]);
    }
    const int color = normalized_accessor(b, values, rgba ? 4 : 3, component_type, rgba ? "VEC4" : "VEC3");
    b.materials.push_back(R"({"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.5,0.5,1],"metallicFactor":0}})");
    b.roots.push_back(
        b.node("{\"mesh\":" +
               std::to_string(b.mesh("[{\"attributes\":{\"POSITION\":" + std::to_string(p) +
                                     ",\"NORMAL\":" + std::to_string(n) + ",\"COLOR_0\":" + std::to_string(color) +
                                     "},\"indices\":" + std::to_string(i) + ",\"material\":0}]")) +
               "}"));
    add_light(b);
    return b;
}

GltfBuilder masked_quad(const std::string& alpha_mode, float factor_alpha, bool textured) {
    GltfBuilder b;
    std::string material = "{\"alphaMode\":\"" + alpha_mode + "\",\"alphaCutoff\":0.5,\"pbrMetallicRoughness\":{" +
                           "\"baseColorFactor\":[1,1,1," + scene_test::json_float(factor_alpha) + "]";
    if (textured) {
        const std::vector<uint8_t> texels = {255, 255, 255, 0, 255, 255, 255, 255,
                                             255, 255, 255, 0, 255, 255, 255, 255};
        const int image = b.image_view(scene_test::png(4, 1, texels, 4));
        b.samplers.push_back(R"({"magFilter":9728,"minFilter":9728,"wrapS":33071,"wrapT":33071})");
        b.textures.push_back("{\"source\":" + std::to_string(image) + ",\"sampler\":0}");
        material += ",\"baseColorTexture\":{\"index\":0}";
    }
    b.materials.push_back(material + "}}");
    b.roots.push_back(
        b.node("{\"mesh\":" + std::to_string(b.mesh("[" + scene_test::unit_quad(b, true, true, 0) + "]")) + "}"));
    add_light(b);
    return b;
}

GltfBuilder skipped_features() {
    GltfBuilder b;
    const std::string quad = scene_test::unit_quad(b);
    const int points = b.vec3s({{0.2f, 0.2f, 0.5f}, {0.8f, 0.8f, 0.5f}});
    const std::string point_primitive = scene_test::primitive(points, -1, -1, -1, -1, -1, 0);
    b.roots.push_back(b.node("{\"mesh\":" + std::to_string(b.mesh("[" + quad + "," + point_primitive + "]")) + "}"));
    b.extensions_used.push_back("KHR_materials_clearcoat");
    add_light(b);
    return b;
}

const std::vector<FeatureFile>& feature_files() {
    static const std::vector<FeatureFile> files = {
        {"skipped_features", [] { return skipped_features(); }},
        {"vertex_colors", [] { return vertex_colors(); }},
        {"vertex_colors_rgba8", [] { return vertex_colors(kUnsignedByte, true); }},
        {"vertex_colors_rgb16", [] { return vertex_colors(kUnsignedShort, false); }},
        {"masked_quad", [] { return masked_quad(); }},
    };
    return files;
}

std::vector<std::filesystem::path> write_all(const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    std::vector<std::filesystem::path> out;
    for (const FeatureFile& file : feature_files()) out.push_back(file.build().write(dir, file.name, true));
    return out;
}

}  // namespace gltf_features
