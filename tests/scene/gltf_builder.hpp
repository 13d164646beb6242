#pragma once
// Writes small glTF files for the scene tests: geometry packed into one buffer (an external .bin
// or an embedded base64 data URI), the rest of the JSON given as text by the test, so a test
// can write exactly the (valid or broken) file it needs.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace scene_test {

namespace fs = std::filesystem;

// glTF component type numbers.
inline constexpr int kByte = 5120;
inline constexpr int kUnsignedByte = 5121;
inline constexpr int kShort = 5122;
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kFloat = 5126;

// A fresh empty directory for one test case, removed with everything in it at destruction.
class TempDir {
public:
    explicit TempDir(const std::string& name);
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return path_; }
    fs::path operator/(const std::string& name) const { return path_ / name; }

private:
    fs::path path_;
};

void write_text(const fs::path& path, const std::string& text);
std::string read_text(const fs::path& path);
std::string base64(const std::vector<uint8_t>& bytes);
std::string json_float(double v);

class GltfBuilder {
public:
    // Each entry is one JSON object, without brackets around the array.
    std::vector<std::string> buffer_views, accessors, meshes, nodes, materials, textures, images, samplers, cameras,
        lights;
    std::vector<int> roots;  // the scene's nodes
    std::vector<std::string> extensions_used, extensions_required;
    std::string top_level_extra;  // appended inside the top-level object, e.g. ",\"x\":1"
    std::vector<uint8_t> bin;

    int view(const void* data, size_t bytes, size_t stride = 0);
    int accessor(int view, int component_type, size_t count, const std::string& type, const std::string& extra = "");
    int vec3s(const std::vector<glm::vec3>& values);  // FLOAT VEC3 with min/max
    int vec2s(const std::vector<glm::vec2>& values);
    int vec4s(const std::vector<glm::vec4>& values);
    int indices(const std::vector<uint32_t>& values, int component_type = kUnsignedShort);
    int image_view(const std::vector<uint8_t>& encoded, const std::string& mime = "image/png");

    int mesh(const std::string& primitives_json_array, const std::string& name = "");
    int node(const std::string& json_object);  // e.g. {"mesh":0,"translation":[1,2,3]}

    std::string json(const std::string& buffer_uri) const;
    // Writes dir/name.gltf, and dir/name.bin unless `embed` (then the buffer is a data URI).
    fs::path write(const fs::path& dir, const std::string& name, bool embed = false) const;
};

// {"attributes":{"POSITION":p,...},"indices":i,"material":m,"mode":mode}; -1 leaves a member out.
std::string primitive(int position, int normal = -1, int uv = -1, int tangent = -1, int indices = -1, int material = -1,
                      int mode = -1);

// A 2-triangle unit quad in z = 0 (corners (0,0),(1,0),(1,1),(0,1), counter-clockwise seen from
// +z) with normals +z and UVs (x, 1 - y) (image top at +y): adds its accessors, returns the
// primitive JSON. `with_normals`/`with_uvs` leave attributes out.
std::string unit_quad(GltfBuilder& b, bool with_normals = true, bool with_uvs = true, int material = -1);

// Encodes an 8-bit image of `channels` (1 to 4) channels as PNG (stb_image_write).
std::vector<uint8_t> png(uint32_t width, uint32_t height, const std::vector<uint8_t>& pixels, int channels = 4);

std::string source_dir();  // the repository root
fs::path shared_scenes();  // <repo>/../shared/scenes

}  // namespace scene_test
