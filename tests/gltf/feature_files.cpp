#include "feature_files.hpp"

#include "animation_files.hpp"

#include <glm/vec4.hpp>

#include <cmath>
#include <cstring>

namespace gltf_features {
namespace {

using scene_test::kFloat;
using scene_test::kShort;
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

GltfBuilder masked_quad(const std::string& alpha_mode, float factor_alpha, bool textured, float u_offset) {
    GltfBuilder b;
    std::string material = "{\"alphaMode\":\"" + alpha_mode + "\",\"alphaCutoff\":0.5,\"pbrMetallicRoughness\":{" +
                           "\"baseColorFactor\":[1,1,1," + scene_test::json_float(factor_alpha) + "]";
    if (textured) {
        const std::vector<uint8_t> texels = {255, 255, 255, 0, 255, 255, 255, 255,
                                             255, 255, 255, 0, 255, 255, 255, 255};
        const int image = b.image_view(scene_test::png(4, 1, texels, 4));
        b.samplers.push_back(R"({"magFilter":9728,"minFilter":9728,"wrapS":33071,"wrapT":33071})");
        b.textures.push_back("{\"source\":" + std::to_string(image) + ",\"sampler\":0}");
        material += ",\"baseColorTexture\":{\"index\":0";
        if (u_offset != 0.0f) {
            material +=
                ",\"extensions\":{\"KHR_texture_transform\":{\"offset\":[" + scene_test::json_float(u_offset) + ",0]}}";
            b.extensions_used.push_back("KHR_texture_transform");
        }
        material += "}";
    }
    b.materials.push_back(material + "}}");
    b.roots.push_back(
        b.node("{\"mesh\":" + std::to_string(b.mesh("[" + scene_test::unit_quad(b, true, true, 0) + "]")) + "}"));
    add_light(b);
    return b;
}

namespace {

// `values` as raw bytes of one bufferView (no stride), for integer attributes and sparse data.
template <typename T>
int raw_view(GltfBuilder& b, const std::vector<T>& values) {
    return b.view(values.data(), values.size() * sizeof(T));
}

std::string pair_json(const float v[2]) {
    return "[" + scene_test::json_float(v[0]) + "," + scene_test::json_float(v[1]) + "]";
}

}  // namespace

GltfBuilder textured_quad(const TexturedQuad& o) {
    GltfBuilder b;
    std::vector<uint8_t> texels;
    for (const auto& t : kStripTexels) {
        for (float c : t) texels.push_back(uint8_t(c * 255.0f));
        texels.push_back(255);
    }
    const int image = b.image_view(scene_test::png(4, 1, texels, 4));
    b.samplers.push_back("{\"magFilter\":9728,\"minFilter\":9728,\"wrapS\":" + std::to_string(o.wrap_s) +
                         ",\"wrapT\":33071}");
    b.textures.push_back("{\"source\":" + std::to_string(image) + ",\"sampler\":0}");
    std::string info = "{\"index\":0,\"texCoord\":" + std::to_string(o.info_tex_coord);
    if (o.transform) {
        info += ",\"extensions\":{\"KHR_texture_transform\":{\"offset\":" + pair_json(o.offset) +
                ",\"rotation\":" + scene_test::json_float(o.rotation) + ",\"scale\":" + pair_json(o.scale);
        if (o.transform_tex_coord >= 0) info += ",\"texCoord\":" + std::to_string(o.transform_tex_coord);
        info += "}}";
        b.extensions_used.push_back("KHR_texture_transform");
    }
    info += "}";
    b.materials.push_back("{\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"baseColorTexture\":" + info + "}}");

    const int set = o.transform && o.transform_tex_coord >= 0 ? o.transform_tex_coord : o.info_tex_coord;
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int n = b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int uv = b.vec2s({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    const int wrong = b.vec2s({{0.9f, 0.5f}, {0.9f, 0.5f}, {0.9f, 0.5f}, {0.9f, 0.5f}});
    const int i = b.indices({0, 1, 2, 0, 2, 3});
    const std::string attributes = "\"POSITION\":" + std::to_string(p) + ",\"NORMAL\":" + std::to_string(n) +
                                   ",\"TEXCOORD_0\":" + std::to_string(set == 1 ? wrong : uv) +
                                   (set == 1 ? ",\"TEXCOORD_1\":" + std::to_string(uv) : std::string());
    b.roots.push_back(b.node("{\"mesh\":" +
                             std::to_string(b.mesh("[{\"attributes\":{" + attributes +
                                                   "},\"indices\":" + std::to_string(i) + ",\"material\":0}]")) +
                             "}"));
    add_light(b);
    return b;
}

GltfBuilder morph_quad(const std::vector<float>& node_weights) {
    GltfBuilder b;
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int n = b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int i = b.indices({0, 1, 2, 0, 2, 3});
    // Target 0's positions: sparse over an all-zero accessor (glTF 2.0 3.6.2.3).
    const int sparse_indices = raw_view(b, std::vector<uint16_t>{1, 2});
    const int sparse_values = raw_view(b, std::vector<glm::vec3>{{0, 0, 2}, {0, 0, 2}});
    const int dp0 =
        b.accessor(-1, kFloat, 4, "VEC3",
                   ",\"sparse\":{\"count\":2,\"indices\":{\"bufferView\":" + std::to_string(sparse_indices) +
                       ",\"componentType\":5123},\"values\":{\"bufferView\":" + std::to_string(sparse_values) + "}}");
    const int dn0 = b.vec3s({{1, 0, -1}, {1, 0, -1}, {1, 0, -1}, {1, 0, -1}});
    const int dp1 = b.vec3s({{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}});
    const std::string primitive =
        "[{\"attributes\":{\"POSITION\":" + std::to_string(p) + ",\"NORMAL\":" + std::to_string(n) +
        "},\"indices\":" + std::to_string(i) + ",\"targets\":[{\"POSITION\":" + std::to_string(dp0) +
        ",\"NORMAL\":" + std::to_string(dn0) + "},{\"POSITION\":" + std::to_string(dp1) + "}]}]";
    b.meshes.push_back("{\"primitives\":" + primitive + ",\"weights\":[0.5,0]}");
    std::string node = "{\"mesh\":" + std::to_string(b.meshes.size() - 1);
    if (!node_weights.empty()) {
        node += ",\"weights\":[";
        for (size_t k = 0; k < node_weights.size(); ++k) {
            node += (k ? "," : "") + scene_test::json_float(node_weights[k]);
        }
        node += "]";
    }
    b.roots.push_back(b.node(node + "}"));
    add_light(b);
    return b;
}

GltfBuilder skinned_quad(float arm_degrees, bool short_joints, bool mirrored) {
    GltfBuilder b;
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int n = b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int i = b.indices({0, 1, 2, 0, 2, 3});
    // Joint slots 2 and 3 name joint 0 at weight 0 (exporters fill unused slots so).
    const std::vector<uint32_t> joint_values = {0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0};
    int joints;
    if (short_joints) {
        std::vector<uint16_t> v(joint_values.begin(), joint_values.end());
        joints = b.accessor(raw_view(b, v), kUnsignedShort, 4, "VEC4");
    } else {
        std::vector<uint8_t> v(joint_values.begin(), joint_values.end());
        joints = b.accessor(raw_view(b, v), kUnsignedByte, 4, "VEC4");
    }
    const std::vector<float> weight_values = {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0};
    const int weights = short_joints ? normalized_accessor(b, weight_values, 4, kUnsignedByte, "VEC4")
                                     : b.vec4s({{1, 0, 0, 0}, {1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}});
    (void)weight_values;
    const std::string primitive = "[{\"attributes\":{\"POSITION\":" + std::to_string(p) +
                                  ",\"NORMAL\":" + std::to_string(n) + ",\"JOINTS_0\":" + std::to_string(joints) +
                                  ",\"WEIGHTS_0\":" + std::to_string(weights) + "},\"indices\":" + std::to_string(i) +
                                  "}]";
    // Column-major inverse bind matrices: identity (hip), T(-0.5, 0, 0) (arm).
    std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,     0, 0, 1,
                              1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -0.5f, 0, 0, 1};
    const int ibm_accessor = b.accessor(raw_view(b, ibm), kFloat, 2, "MAT4");
    const double half = 0.5 * arm_degrees * 3.14159265358979323846 / 180.0;
    const int mesh = b.mesh(primitive);
    const int arm =
        b.node("{\"name\":\"arm\",\"translation\":[0.5,0,0],\"rotation\":[0," + scene_test::json_float(std::sin(half)) +
               ",0," + scene_test::json_float(std::cos(half)) + "]}");
    const int hip = b.node("{\"name\":\"hip\"," + std::string(mirrored ? "\"scale\":[-1,1,1]," : "") +
                           "\"children\":[" + std::to_string(arm) + "]}");
    const int body = b.node("{\"mesh\":" + std::to_string(mesh) + ",\"skin\":0,\"translation\":[5,5,5]}");
    b.top_level_extra = ",\"skins\":[{\"joints\":[" + std::to_string(hip) + "," + std::to_string(arm) +
                        "],\"inverseBindMatrices\":" + std::to_string(ibm_accessor) + "}]";
    b.roots.push_back(hip);
    b.roots.push_back(body);
    add_light(b);
    return b;
}

GltfBuilder two_cameras() {
    GltfBuilder b;
    b.roots.push_back(b.node("{\"mesh\":" + std::to_string(b.mesh("[" + scene_test::unit_quad(b) + "]")) + "}"));
    b.cameras.push_back(R"({"type":"perspective","perspective":{"yfov":0.8,"znear":0.1,"zfar":10}})");
    b.cameras.push_back(
        R"({"name":"top","type":"orthographic","orthographic":{"xmag":0.625,"ymag":0.625,"znear":0.1,"zfar":10}})");
    b.roots.push_back(b.node(R"({"camera":0,"translation":[0.5,0.5,2]})"));
    b.roots.push_back(b.node(R"({"camera":1,"translation":[0.5,0.5,1]})"));
    add_light(b);
    return b;
}

GltfBuilder quantized_quad(int position_type, bool declare) {
    GltfBuilder b;
    const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    int p;
    std::string scale = "1";
    if (position_type == kShort) {
        // Unnormalized shorts, dequantized by the node's scale; each element padded to 8 bytes.
        std::vector<int16_t> q;
        for (const auto& c : corners) q.insert(q.end(), {int16_t(c[0] * 1000), int16_t(c[1] * 1000), 0, 0});
        p = b.accessor(b.view(q.data(), q.size() * 2, 8), kShort, 4, "VEC3", ",\"min\":[0,0,0],\"max\":[1000,1000,0]");
        scale = "0.001";
    } else {
        std::vector<uint16_t> q;
        for (const auto& c : corners) q.insert(q.end(), {uint16_t(c[0] * 65535), uint16_t(c[1] * 65535), 0, 0});
        p = b.accessor(b.view(q.data(), q.size() * 2, 8), kUnsignedShort, 4, "VEC3",
                       ",\"normalized\":true,\"min\":[0,0,0],\"max\":[1,1,0]");
    }
    std::vector<int8_t> normals;
    for (int k = 0; k < 4; ++k) normals.insert(normals.end(), {0, 0, 127, 0});
    const int n =
        b.accessor(b.view(normals.data(), normals.size(), 4), scene_test::kByte, 4, "VEC3", ",\"normalized\":true");
    std::vector<uint8_t> uvs;
    for (const auto& c : corners) uvs.insert(uvs.end(), {uint8_t(c[0] * 255), uint8_t((1 - c[1]) * 255), 0, 0});
    const int uv = b.accessor(b.view(uvs.data(), uvs.size(), 4), kUnsignedByte, 4, "VEC2", ",\"normalized\":true");
    const int i = b.indices({0, 1, 2, 0, 2, 3});
    b.roots.push_back(b.node("{\"mesh\":" + std::to_string(b.mesh("[" + scene_test::primitive(p, n, uv, -1, i) + "]")) +
                             ",\"scale\":[" + scale + "," + scale + "," + scale + "]}"));
    if (declare) {
        b.extensions_used.push_back("KHR_mesh_quantization");
        b.extensions_required.push_back("KHR_mesh_quantization");
    }
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
    // An animation moving node 0: one key at t = 0 (the still frame stays the node's own transform).
    const std::vector<float> times = {0.0f};
    const int input = b.accessor(raw_view(b, times), kFloat, 1, "SCALAR", ",\"min\":[0],\"max\":[0]");
    const int output = b.vec3s({{0, 0, 1}});
    b.top_level_extra =
        ",\"animations\":[{\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":"
        "\"translation\"}}],\"samplers\":[{\"input\":" +
        std::to_string(input) + ",\"output\":" + std::to_string(output) + "}]}]";
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
        {"texture_transform",
         [] {
             TexturedQuad o;
             o.transform = true;
             o.rotation = 1.5707963f;
             o.offset[1] = 1.0f;
             return textured_quad(o);
         }},
        {"morph_targets", [] { return morph_quad(); }},
        {"skinned_quad", [] { return skinned_quad(90.0f); }},
        {"two_cameras", [] { return two_cameras(); }},
        {"quantized_quad", [] { return quantized_quad(kUnsignedShort); }},
        {"animated_scene", [] { return animated_scene(); }},
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
