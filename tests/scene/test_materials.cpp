// Materials, textures, images and samplers: factors and flags as written, images decoded to the
// exact RGBA8 values written with stb_image_write (PNG is lossless: exact comparison), each image
// kept once, the sRGB/linear use recorded, unused images neither decoded nor required, and the
// glTF default material for primitives without one. Also: a .glb loads like its .gltf.

#include "gltf_builder.hpp"
#include "vplkit/error.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>

#include <cstring>
#include <fstream>

using namespace vplkit::scene;
using namespace scene_test;

namespace {

const std::vector<uint8_t> kPixelsA = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 128, 10, 20, 30, 40};  // 2x2
const std::vector<uint8_t> kPixelsB = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};                           // 4x1 RGB
const std::vector<uint8_t> kPixelsC = {128, 128, 255, 255};                                              // 1x1

// Images: 0 external file, 1 in a bufferView, 2 a data URI, 3 an external file that does not
// exist. Textures: 0 and 3 both show image 0 (0 with a sampler), 1 image 1, 2 image 2, 4 the
// missing image 3, which no material uses (so it must not be required).
fs::path write_textured(const fs::path& dir) {
    GltfBuilder b;
    const auto a = png(2, 2, kPixelsA);
    std::ofstream(dir / "albedo.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(a.data()), std::streamsize(a.size()));
    b.images.push_back(R"({"uri":"albedo.png"})");
    b.image_view(png(4, 1, kPixelsB, 3));
    b.images.push_back(R"({"uri":"data:image/png;base64,)" + base64(png(1, 1, kPixelsC)) + "\"}");
    b.images.push_back(R"({"uri":"unused_missing.png"})");
    b.samplers.push_back(R"({"magFilter":9728,"minFilter":9986,"wrapS":33071,"wrapT":33648})");
    b.textures = {R"({"source":0,"sampler":0})", R"({"source":1})", R"({"source":2})", R"({"source":0})",
                  R"({"source":3})"};
    b.materials.push_back(
        R"({"name":"painted","pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,1,0.75],)"
        R"("baseColorTexture":{"index":0},)"
        R"("metallicFactor":0.2,"roughnessFactor":0.7,"metallicRoughnessTexture":{"index":1}},)"
        R"("normalTexture":{"index":2,"scale":0.5},"emissiveFactor":[1,0.5,0],"emissiveTexture":{"index":3},)"
        R"("extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":3}},)"
        R"("alphaMode":"MASK","alphaCutoff":0.3,"doubleSided":true})");
    b.materials.push_back(
        R"({"name":"glass","alphaMode":"BLEND","pbrMetallicRoughness":{"metallicRoughnessTexture":{"index":3}}})");
    b.extensions_used = {"KHR_materials_emissive_strength"};
    b.mesh("[" + unit_quad(b, true, true, 0) + "," + unit_quad(b, true, true, 1) + "," + unit_quad(b) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    return b.write(dir, "textured");
}

}  // namespace

TEST_CASE("material factors and flags and the default material") {
    TempDir dir("materials");
    const Scene s = load_gltf(write_textured(dir.path()));
    REQUIRE(s.materials.size() == 3);  // the file's two and the default one
    const Material& m = s.materials[0];
    CHECK(m.name == "painted");
    CHECK(m.base_color_factor == glm::vec4(0.5f, 0.25f, 1.0f, 0.75f));
    CHECK(m.metallic_factor == 0.2f);
    CHECK(m.roughness_factor == 0.7f);
    CHECK(m.normal_scale == 0.5f);
    CHECK(m.emissive_factor == glm::vec3(1.0f, 0.5f, 0.0f));
    CHECK(m.emissive_strength == 3.0f);
    CHECK(m.emission() == glm::vec3(3.0f, 1.5f, 0.0f));
    CHECK(m.alpha_mode == AlphaMode::mask);
    CHECK(m.alpha_cutoff == 0.3f);
    CHECK(m.double_sided);

    const Material& glass = s.materials[1];
    CHECK(glass.alpha_mode == AlphaMode::blend);
    CHECK(!glass.double_sided);
    CHECK(glass.base_color_texture == kNoTexture);
    CHECK(glass.base_color_factor == glm::vec4(1.0f));
    CHECK(!glass.emits());

    const Material& fallback = s.materials[2];  // glTF 2.0's default material
    CHECK(fallback.name == "default");
    CHECK(fallback.base_color_factor == glm::vec4(1.0f));
    CHECK(fallback.metallic_factor == 1.0f);
    CHECK(fallback.roughness_factor == 1.0f);
    CHECK(fallback.alpha_mode == AlphaMode::opaque);

    REQUIRE(s.primitives.size() == 3);
    CHECK(s.primitives[0].material == 0);
    CHECK(s.primitives[1].material == 1);
    CHECK(s.primitives[2].material == 2);
    CHECK(s.primitives[0].tangents == TangentSource::generated);  // normal-textured
    CHECK(s.primitives[1].tangents == TangentSource::none);
    CHECK(s.emissive_triangles == std::vector<uint32_t>{0, 1});  // the first quad's two triangles
}

TEST_CASE("textures and images: decoded pixels and shared images and colour spaces and samplers") {
    TempDir dir("textures");
    const Scene s = load_gltf(write_textured(dir.path()));
    const Material& m = s.materials[0];
    // Textures in order of first use: painted's base colour (file 0), metallic-roughness (1),
    // normal (2), emissive (3); glass reuses 3. Texture 4 (the missing image) is not kept.
    REQUIRE(s.textures.size() == 4);
    REQUIRE(s.images.size() == 3);
    CHECK(m.base_color_texture == 0);
    CHECK(m.metallic_roughness_texture == 1);
    CHECK(m.normal_texture == 2);
    CHECK(m.emissive_texture == 3);
    CHECK(s.materials[1].metallic_roughness_texture == 3);
    CHECK(s.textures[0].image == s.textures[3].image);  // one image behind two textures

    const Image& albedo = s.images[s.textures[0].image];
    CHECK(albedo.name == "albedo.png");
    CHECK(albedo.width == 2);
    CHECK(albedo.height == 2);
    CHECK(albedo.rgba == kPixelsA);
    CHECK(albedo.srgb);    // base colour and emissive
    CHECK(albedo.linear);  // glass's metallic-roughness
    const Image& packed = s.images[s.textures[1].image];
    CHECK(packed.width == 4);
    CHECK(packed.height == 1);
    // 3 channels written, RGBA read: alpha 255 added.
    CHECK(packed.rgba == std::vector<uint8_t>{1, 2, 3, 255, 4, 5, 6, 255, 7, 8, 9, 255, 10, 11, 12, 255});
    CHECK(!packed.srgb);
    CHECK(packed.linear);
    const Image& normal = s.images[s.textures[2].image];
    CHECK(normal.rgba == kPixelsC);
    CHECK(normal.linear);
    CHECK(!normal.srgb);

    const Sampler& sampler = s.textures[0].sampler;
    CHECK(sampler.mag_filter == Filter::nearest);
    CHECK(sampler.min_filter == Filter::nearest);
    CHECK(sampler.mipmap_mode == MipmapMode::linear);
    CHECK(sampler.wrap_s == Wrap::clamp_to_edge);
    CHECK(sampler.wrap_t == Wrap::mirrored_repeat);
    const Sampler& plain = s.textures[1].sampler;  // no sampler: repeat, linear, linear mipmaps
    CHECK(plain.wrap_s == Wrap::repeat);
    CHECK(plain.mag_filter == Filter::linear);
    CHECK(plain.mipmap_mode == MipmapMode::linear);
}

TEST_CASE("a binary glb loads like the same gltf") {
    TempDir dir("glb");
    GltfBuilder b;
    b.mesh("[" + unit_quad(b) + "]");
    b.node(R"({"mesh":0,"translation":[0,0,-2]})");
    b.roots = {0};
    const Scene from_gltf = load_gltf(b.write(dir.path(), "quad"));

    // GLB: 12-byte header, then a JSON chunk and a BIN chunk, each 4-byte aligned.
    std::string json = b.json("");
    json.replace(json.find(",\"uri\":\"\""), 9, "");  // the GLB buffer has no uri
    while (json.size() % 4) json += ' ';
    std::vector<uint8_t> bin = b.bin;
    while (bin.size() % 4) bin.push_back(0);
    std::vector<uint8_t> glb;
    auto u32 = [&](uint32_t v) {
        glb.insert(glb.end(), reinterpret_cast<uint8_t*>(&v), reinterpret_cast<uint8_t*>(&v) + 4);
    };
    u32(0x46546C67);  // "glTF"
    u32(2);
    u32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
    u32(uint32_t(json.size()));
    u32(0x4E4F534A);  // "JSON"
    glb.insert(glb.end(), json.begin(), json.end());
    u32(uint32_t(bin.size()));
    u32(0x004E4942);  // "BIN\0"
    glb.insert(glb.end(), bin.begin(), bin.end());
    const fs::path path = dir / "quad.glb";
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));

    const Scene from_glb = load_gltf(path);
    REQUIRE(from_glb.vertices.size() == from_gltf.vertices.size());
    CHECK(std::memcmp(from_glb.vertices.data(), from_gltf.vertices.data(), from_glb.vertices.size() * sizeof(Vertex)) ==
          0);
    CHECK(from_glb.indices == from_gltf.indices);
    CHECK(from_glb.vertices[0].position == glm::vec3(0, 0, -2));
}

TEST_CASE("factors outside their range are clamped with a warning and negative emission is an error") {
    TempDir dir("factor_range");
    GltfBuilder b;
    b.materials.push_back(
        R"({"name":"hot","pbrMetallicRoughness":{"baseColorFactor":[1.2,0.5,-0.1,1],"roughnessFactor":1.5},)"
        R"("emissiveFactor":[4,0,0]})");
    b.mesh("[" + unit_quad(b, true, true, 0) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const Scene s = load_gltf(b.write(dir.path(), "clamped"));
    CHECK(s.materials[0].base_color_factor == glm::vec4(1.0f, 0.5f, 0.0f, 1.0f));
    CHECK(s.materials[0].roughness_factor == 1.0f);
    CHECK(s.materials[0].emission() == glm::vec3(4, 0, 0));  // above 1 is kept: a bright emitter
    REQUIRE(s.warnings.messages.size() == 1);
    CHECK(s.warnings.messages[0].find("material 0 'hot'") != std::string::npos);

    b.materials[0] = R"({"emissiveFactor":[0,-1,0]})";
    const fs::path negative = b.write(dir.path(), "negative");
    CHECK_THROWS_WITH_AS(load_gltf(negative),
                         (negative.string() + ": material 0: emissiveFactor is negative or not finite").c_str(),
                         vplkit::Error);
}
