// Bad input: each malformed file (written into a temporary folder) gets one vplkit::Error, on one
// line, that starts with the file's path and names the problem; degenerate triangles are dropped
// and counted instead.

#include "gltf_builder.hpp"
#include "vplkit/error.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>

#include <cstring>
#include <fstream>
#include <limits>

using namespace vplkit::scene;
using namespace scene_test;

namespace {

// Loads `path` and returns the error message ("" when it loaded).
std::string load_error(const fs::path& path, const LoadOptions& options = {}) {
    try {
        (void)load_gltf(path, options);
    } catch (const vplkit::Error& e) {
        return e.what();
    }
    return "";
}

// The message names the file first, is one line, and contains every fragment.
void check_error(const std::string& message, const fs::path& file, std::initializer_list<const char*> fragments) {
    INFO("message: " << message);
    REQUIRE(!message.empty());
    CHECK(message.rfind(file.string() + ": ", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
    for (const char* fragment : fragments) CHECK(message.find(fragment) != std::string::npos);
}

// A valid one-quad file; tests break it in one place each.
GltfBuilder quad_builder() {
    GltfBuilder b;
    b.mesh("[" + unit_quad(b) + "]", "quad");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    return b;
}

void put_float(std::vector<uint8_t>& bin, size_t offset, float value) {
    std::memcpy(bin.data() + offset, &value, 4);
}

}  // namespace

TEST_CASE("bad input: the file does not exist") {
    TempDir dir("missing_file");
    check_error(load_error(dir / "nothing.gltf"), dir / "nothing.gltf", {"file not found"});
}

TEST_CASE("bad input: malformed JSON") {
    TempDir dir("malformed_json");
    const fs::path path = quad_builder().write(dir.path(), "broken");
    const std::string text = read_text(path);
    write_text(path, text.substr(0, text.size() / 2));  // cut off mid-object
    check_error(load_error(path), path, {"malformed JSON", "parse error at line 1"});
}

TEST_CASE("bad input: the .bin buffer is missing") {
    TempDir dir("missing_bin");
    const fs::path path = quad_builder().write(dir.path(), "model");
    fs::remove(dir / "model.bin");
    check_error(load_error(path), path, {"buffer file", (dir.path() / "model.bin").string().c_str(), "not found"});
}

TEST_CASE("a buffer URI that is an absolute path is that file (RFC 3986), and its absence names it") {
    TempDir dir("absolute_uri");
    const fs::path path = quad_builder().write(dir.path(), "model");
    const fs::path elsewhere = dir / "elsewhere";
    fs::create_directories(elsewhere);
    fs::rename(dir / "model.bin", elsewhere / "model.bin");
    const std::string text = read_text(path);
    const std::string relative = "\"uri\":\"model.bin\"";
    REQUIRE(text.find(relative) != std::string::npos);
    std::string absolute = text;
    absolute.replace(text.find(relative), relative.size(), "\"uri\":\"" + (elsewhere / "model.bin").string() + "\"");
    write_text(path, absolute);
    CHECK(vplkit::scene::load_gltf(path).triangle_count() == 2);
    fs::remove(elsewhere / "model.bin");
    check_error(load_error(path), path, {"buffer file", (elsewhere / "model.bin").string().c_str(), "not found"});
}

TEST_CASE("bad input: the .bin buffer is truncated") {
    TempDir dir("truncated_bin");
    const fs::path path = quad_builder().write(dir.path(), "model");
    fs::resize_file(dir / "model.bin", 20);
    check_error(load_error(path), path,
                {"buffer file", (dir.path() / "model.bin").string().c_str(), "has 20 bytes", "declares 140"});
}

TEST_CASE("bad input: a texture file is missing") {
    TempDir dir("missing_texture");
    GltfBuilder b;
    b.images.push_back(R"({"uri":"brick%20wall.png"})");
    b.textures.push_back(R"({"source":0})");
    b.materials.push_back(R"({"name":"wall","pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})");
    b.mesh("[" + unit_quad(b, true, true, 0) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const fs::path path = b.write(dir.path(), "textured");
    check_error(
        load_error(path), path,
        {"brick%20wall.png", (dir.path() / "brick wall.png").string().c_str(), "not found", "material 0 'wall'"});
}

TEST_CASE("bad input: a texture file that is not an image") {
    TempDir dir("undecodable_texture");
    write_text(dir / "noise.png", "this is not a PNG");
    GltfBuilder b;
    b.images.push_back(R"({"uri":"noise.png"})");
    b.textures.push_back(R"({"source":0})");
    b.materials.push_back(R"({"emissiveFactor":[1,1,1],"emissiveTexture":{"index":0}})");
    b.mesh("[" + unit_quad(b, true, true, 0) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const fs::path path = b.write(dir.path(), "textured");
    check_error(load_error(path), path, {"noise.png", "cannot be decoded", "emissive texture"});
}

TEST_CASE("bad input: an accessor reads past the end of its bufferView") {
    TempDir dir("accessor_bounds");
    GltfBuilder b = quad_builder();
    b.accessors[0].replace(b.accessors[0].find("\"count\":4"), 9, "\"count\":40");
    const fs::path path = b.write(dir.path(), "model");
    check_error(load_error(path), path,
                {"accessor 0 (POSITION of mesh 0 'quad' primitive 0)", "40 element", "bufferView 0 has only 48 bytes"});
}

TEST_CASE("bad input: a bufferView lies outside its buffer") {
    TempDir dir("view_bounds");
    GltfBuilder b = quad_builder();
    b.buffer_views[1] = R"({"buffer":0,"byteOffset":48,"byteLength":4800})";
    const fs::path path = b.write(dir.path(), "model");
    check_error(load_error(path), path, {"bufferView 1", "48 + 4800", "model.bin"});
}

TEST_CASE("bad input: an index beyond the vertices") {
    TempDir dir("index_range");
    GltfBuilder b;
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int i = b.indices({0, 1, 7});
    b.mesh("[" + primitive(p, -1, -1, -1, i) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const fs::path path = b.write(dir.path(), "model");
    check_error(load_error(path), path, {"index 2 is 7", "3 vertices"});
}

TEST_CASE("bad input: NaN and infinite positions") {
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        TempDir dir("nan_position");
        GltfBuilder b = quad_builder();
        put_float(b.bin, 12 * 2 + 4, bad);  // vertex 2's y
        const fs::path path = b.write(dir.path(), "model");
        check_error(load_error(path), path, {"POSITION of vertex 2", std::isnan(bad) ? "nan" : "inf"});
    }
}

TEST_CASE("bad input: a transform that overflows float") {
    TempDir dir("overflow");
    GltfBuilder b = quad_builder();
    b.nodes[0] = R"({"mesh":0,"scale":[1e30,1e30,1e30],"children":[1]})";
    b.node(R"({"mesh":0,"scale":[1e30,1e30,1e30]})");
    const fs::path path = b.write(dir.path(), "model");
    check_error(load_error(path), path, {"node 1", "not finite in world space"});
}

TEST_CASE("bad input: degenerate triangles are dropped and counted") {
    TempDir dir("degenerate");
    GltfBuilder b;
    // A good triangle, one repeating a vertex, one with collinear corners, one far thinner than
    // float can resolve against its length.
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 1e-9f, 0}});
    const int i = b.indices({0, 1, 2, 0, 1, 1, 0, 1, 3, 0, 3, 4});
    b.mesh("[" + primitive(p, -1, -1, -1, i) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const Scene s = load_gltf(b.write(dir.path(), "model"));
    CHECK(s.triangle_count() == 1);
    CHECK(s.warnings.degenerate_triangles == 3);
}

TEST_CASE("bad input: no geometry") {
    TempDir dir("no_geometry");
    {
        GltfBuilder b;  // only a point primitive
        const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        b.mesh("[" + primitive(p, -1, -1, -1, -1, -1, 0) + "]");
        b.node(R"({"mesh":0})");
        b.roots = {0};
        const fs::path path = b.write(dir.path(), "points");
        check_error(load_error(path), path, {"no triangles", "1 non-triangle primitive(s) skipped"});
    }
    {
        GltfBuilder b;  // every triangle degenerate
        const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}});
        b.mesh("[" + primitive(p) + "]");
        b.node(R"({"mesh":0})");
        b.roots = {0};
        const fs::path path = b.write(dir.path(), "flat");
        check_error(load_error(path), path, {"no triangles", "1 degenerate triangle(s) dropped"});
    }
    {
        GltfBuilder b;  // nodes but no mesh at all
        b.node(R"({"name":"empty"})");
        b.roots = {0};
        const fs::path path = b.write(dir.path(), "empty");
        check_error(load_error(path), path, {"no triangles"});
    }
}

TEST_CASE("bad input: an unknown required extension") {
    TempDir dir("required_extension");
    GltfBuilder b = quad_builder();
    b.extensions_used = {"KHR_draco_mesh_compression"};
    b.extensions_required = {"KHR_draco_mesh_compression"};
    const fs::path path = b.write(dir.path(), "model");
    check_error(load_error(path), path, {"requires extension KHR_draco_mesh_compression", "not support"});

    // A supported extension may be required; an unsupported one that is only used is a warning.
    GltfBuilder ok = quad_builder();
    ok.extensions_used = {"KHR_lights_punctual", "KHR_materials_sheen"};
    ok.extensions_required = {"KHR_lights_punctual"};
    const Scene s = load_gltf(ok.write(dir.path(), "fine"));
    REQUIRE(s.warnings.messages.size() == 1);
    CHECK(s.warnings.messages[0].find("KHR_materials_sheen") != std::string::npos);
}

TEST_CASE("bad input: a camera that does not exist") {
    TempDir dir("camera_index");
    LoadOptions options;
    options.camera = 3;
    GltfBuilder b = quad_builder();
    b.cameras.push_back(R"({"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}})");
    b.node(R"({"camera":0})");
    b.roots = {0, 1};
    const fs::path with_one = b.write(dir.path(), "one_camera");
    check_error(load_error(with_one, options), with_one, {"camera 3 was asked for", "has 1 (0..0)"});
    const fs::path with_none = quad_builder().write(dir.path(), "no_camera");
    options.camera = 0;
    check_error(load_error(with_none, options), with_none, {"camera 0 was asked for", "no camera"});
}

TEST_CASE("bad input: references to things the file does not have") {
    TempDir dir("references");
    {
        GltfBuilder b = quad_builder();
        b.nodes[0] = R"({"mesh":4})";
        const fs::path path = b.write(dir.path(), "mesh");
        check_error(load_error(path), path, {"node 0 refers to mesh 4", "1 mesh"});
    }
    {
        GltfBuilder b = quad_builder();
        b.meshes[0] = "{\"primitives\":[" + primitive(0, 1, 2, -1, 3, 9) + "]}";
        const fs::path path = b.write(dir.path(), "material");
        check_error(load_error(path), path, {"refers to material 9"});
    }
    {
        GltfBuilder b = quad_builder();
        b.nodes[0] = R"({"mesh":0,"children":[0]})";  // its own child
        const fs::path path = b.write(dir.path(), "cycle");
        check_error(load_error(path), path, {"node 0", "appears twice"});
    }
    {
        GltfBuilder b = quad_builder();
        b.materials.push_back(R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":2}}})");
        const fs::path path = b.write(dir.path(), "texture");
        check_error(load_error(path), path, {"base colour texture of material 0", "refers to texture 2"});
    }
}
