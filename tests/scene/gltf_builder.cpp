#include "gltf_builder.hpp"

#include <glm/common.hpp>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace scene_test {

TempDir::TempDir(const std::string& name) {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() /
            ("vplkit_scene_" + name + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
}

void write_text(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= bytes[i + 2];
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? digits[v & 63] : '=';
    }
    return out;
}

std::string json_float(double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

int GltfBuilder::view(const void* data, size_t bytes, size_t stride) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    bin.resize(offset + bytes);
    std::memcpy(bin.data() + offset, data, bytes);
    std::string v =
        "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" + std::to_string(bytes);
    if (stride) v += ",\"byteStride\":" + std::to_string(stride);
    buffer_views.push_back(v + "}");
    return int(buffer_views.size() - 1);
}

int GltfBuilder::accessor(int view_index, int component_type, size_t count, const std::string& type,
                          const std::string& extra) {
    std::string a = "{";
    if (view_index >= 0) a += "\"bufferView\":" + std::to_string(view_index) + ",";
    a += "\"componentType\":" + std::to_string(component_type) + ",\"count\":" + std::to_string(count) +
         ",\"type\":\"" + type + "\"" + extra + "}";
    accessors.push_back(a);
    return int(accessors.size() - 1);
}

int GltfBuilder::vec3s(const std::vector<glm::vec3>& values) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const auto& v : values) lo = glm::min(lo, v), hi = glm::max(hi, v);
    const std::string bounds = ",\"min\":[" + json_float(lo.x) + "," + json_float(lo.y) + "," + json_float(lo.z) +
                               "],\"max\":[" + json_float(hi.x) + "," + json_float(hi.y) + "," + json_float(hi.z) + "]";
    return accessor(view(values.data(), values.size() * 12), kFloat, values.size(), "VEC3", bounds);
}

int GltfBuilder::vec2s(const std::vector<glm::vec2>& values) {
    return accessor(view(values.data(), values.size() * 8), kFloat, values.size(), "VEC2");
}

int GltfBuilder::vec4s(const std::vector<glm::vec4>& values) {
    return accessor(view(values.data(), values.size() * 16), kFloat, values.size(), "VEC4");
}

int GltfBuilder::indices(const std::vector<uint32_t>& values, int component_type) {
    std::vector<uint8_t> bytes;
    for (uint32_t v : values) {
        if (component_type == kUnsignedByte) {
            bytes.push_back(uint8_t(v));
        } else if (component_type == kUnsignedShort) {
            const uint16_t s = uint16_t(v);
            bytes.insert(bytes.end(), reinterpret_cast<const uint8_t*>(&s), reinterpret_cast<const uint8_t*>(&s) + 2);
        } else {
            bytes.insert(bytes.end(), reinterpret_cast<const uint8_t*>(&v), reinterpret_cast<const uint8_t*>(&v) + 4);
        }
    }
    return accessor(view(bytes.data(), bytes.size()), component_type, values.size(), "SCALAR");
}

int GltfBuilder::image_view(const std::vector<uint8_t>& encoded, const std::string& mime) {
    const int v = view(encoded.data(), encoded.size());
    images.push_back("{\"bufferView\":" + std::to_string(v) + ",\"mimeType\":\"" + mime + "\"}");
    return int(images.size() - 1);
}

int GltfBuilder::mesh(const std::string& primitives, const std::string& name) {
    meshes.push_back("{" + (name.empty() ? std::string() : "\"name\":\"" + name + "\",") +
                     "\"primitives\":" + primitives + "}");
    return int(meshes.size() - 1);
}

int GltfBuilder::node(const std::string& json_object) {
    nodes.push_back(json_object);
    return int(nodes.size() - 1);
}

namespace {

std::string array(const char* name, const std::vector<std::string>& items) {
    if (items.empty()) return "";
    std::string out = ",\"" + std::string(name) + "\":[";
    for (size_t i = 0; i < items.size(); ++i) out += (i ? "," : "") + items[i];
    return out + "]";
}

std::string string_array(const char* name, const std::vector<std::string>& items) {
    std::vector<std::string> quoted;
    for (const auto& item : items) quoted.push_back("\"" + item + "\"");
    return array(name, quoted);
}

}  // namespace

std::string GltfBuilder::json(const std::string& buffer_uri) const {
    std::string out = "{\"asset\":{\"version\":\"2.0\",\"generator\":\"vplkit scene tests\"}";
    std::vector<std::string> root_text;
    for (int r : roots) root_text.push_back(std::to_string(r));
    std::string scene_nodes = "[";
    for (size_t i = 0; i < root_text.size(); ++i) scene_nodes += (i ? "," : "") + root_text[i];
    out += ",\"scene\":0,\"scenes\":[{\"nodes\":" + scene_nodes + "]}]";
    out += array("nodes", nodes) + array("meshes", meshes) + array("materials", materials) +
           array("textures", textures) + array("images", images) + array("samplers", samplers) +
           array("cameras", cameras) + array("accessors", accessors) + array("bufferViews", buffer_views);
    if (!bin.empty()) {
        out += ",\"buffers\":[{\"byteLength\":" + std::to_string(bin.size()) + ",\"uri\":\"" + buffer_uri + "\"}]";
    }
    out += string_array("extensionsUsed", extensions_used) + string_array("extensionsRequired", extensions_required);
    if (!lights.empty()) {
        std::string list;
        for (size_t i = 0; i < lights.size(); ++i) list += (i ? "," : "") + lights[i];
        out += ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[" + list + "]}}";
    }
    return out + top_level_extra + "}";
}

fs::path GltfBuilder::write(const fs::path& dir, const std::string& name, bool embed) const {
    const fs::path gltf = dir / (name + ".gltf");
    if (embed) {
        write_text(gltf, json("data:application/octet-stream;base64," + base64(bin)));
    } else {
        write_text(gltf, json(name + ".bin"));
        std::ofstream out(dir / (name + ".bin"), std::ios::binary);
        out.write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
    }
    return gltf;
}

std::string primitive(int position, int normal, int uv, int tangent, int indices, int material, int mode) {
    std::string a = "\"POSITION\":" + std::to_string(position);
    if (normal >= 0) a += ",\"NORMAL\":" + std::to_string(normal);
    if (uv >= 0) a += ",\"TEXCOORD_0\":" + std::to_string(uv);
    if (tangent >= 0) a += ",\"TANGENT\":" + std::to_string(tangent);
    std::string p = "{\"attributes\":{" + a + "}";
    if (indices >= 0) p += ",\"indices\":" + std::to_string(indices);
    if (material >= 0) p += ",\"material\":" + std::to_string(material);
    if (mode >= 0) p += ",\"mode\":" + std::to_string(mode);
    return p + "}";
}

std::string unit_quad(GltfBuilder& b, bool with_normals, bool with_uvs, int material) {
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int n = with_normals ? b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}) : -1;
    const int uv = with_uvs ? b.vec2s({{0, 1}, {1, 1}, {1, 0}, {0, 0}}) : -1;
    const int i = b.indices({0, 1, 2, 0, 2, 3});
    return primitive(p, n, uv, -1, i, material);
}

std::vector<uint8_t> png(uint32_t width, uint32_t height, const std::vector<uint8_t>& pixels, int channels) {
    std::vector<uint8_t> out;
    stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* bytes = static_cast<std::vector<uint8_t>*>(context);
            bytes->insert(bytes->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
        },
        &out, int(width), int(height), channels, pixels.data(), int(width) * channels);
    if (out.empty()) throw std::runtime_error("stb_image_write failed");
    return out;
}

std::string source_dir() {
    return VPLKIT_SOURCE_DIR;
}

fs::path shared_scenes() {
    return (fs::path(VPLKIT_SOURCE_DIR) / ".." / "shared" / "scenes").lexically_normal();
}

}  // namespace scene_test
