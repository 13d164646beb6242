// Accessor forms the loader reads itself (tinygltf only parses them): interleaved views with a
// byteStride, sparse substitution, normalized integer texture coordinates, 8-bit indices, and an
// embedded image whose bufferView does not fit its buffer (an error, not a read past the end).
// Values are exact: they are copied or divided by 65535 once.

#include "gltf_builder.hpp"
#include "vplkit/error.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>

#include <cstring>

using namespace vplkit::scene;
using namespace scene_test;

TEST_CASE("interleaved and sparse and normalized accessors") {
    TempDir dir("accessors");
    GltfBuilder b;
    // Interleaved position + normal, 24 bytes a vertex.
    const float interleaved[4][6] = {{0, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 1}, {1, 1, 0, 0, 0, 1}, {0, 1, 0, 0, 0, 1}};
    const int v = b.view(interleaved, sizeof interleaved, 24);
    // Sparse: vertex 2 moves from (1,1,0) to (2,2,0).
    const uint8_t sparse_index = 2;
    const float sparse_value[3] = {2, 2, 0};
    const int iv = b.view(&sparse_index, 1);
    const int vv = b.view(sparse_value, 12);
    const int position =
        b.accessor(v, kFloat, 4, "VEC3",
                   R"(,"min":[0,0,0],"max":[2,2,0],"sparse":{"count":1,"indices":{"bufferView":)" + std::to_string(iv) +
                       R"(,"componentType":5121},"values":{"bufferView":)" + std::to_string(vv) + "}}");
    const int normal = b.accessor(v, kFloat, 4, "VEC3", R"(,"byteOffset":12)");
    const uint16_t uv[8] = {0, 65535, 65535, 65535, 65535, 0, 0, 32768};
    const int uvs = b.accessor(b.view(uv, sizeof uv), kUnsignedShort, 4, "VEC2", R"(,"normalized":true)");
    const int indices = b.indices({0, 1, 2, 0, 2, 3}, kUnsignedByte);
    b.mesh("[" + primitive(position, normal, uvs, -1, indices) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const Scene s = load_gltf(b.write(dir.path(), "accessors"));
    REQUIRE(s.vertices.size() == 4);
    CHECK(s.vertices[0].position == glm::vec3(0, 0, 0));
    CHECK(s.vertices[1].position == glm::vec3(1, 0, 0));
    CHECK(s.vertices[2].position == glm::vec3(2, 2, 0));  // the sparse value
    CHECK(s.vertices[3].position == glm::vec3(0, 1, 0));
    for (const Vertex& vertex : s.vertices) CHECK(vertex.normal == glm::vec3(0, 0, 1));
    CHECK(s.vertices[0].uv0 == glm::vec2(0, 1));
    CHECK(s.vertices[2].uv0 == glm::vec2(1, 0));
    CHECK(s.vertices[3].uv0 == glm::vec2(0, 32768.0f / 65535.0f));
    CHECK(s.indices == std::vector<uint32_t>{0, 1, 2, 0, 2, 3});
}

TEST_CASE("a sparse index outside the accessor is an error") {
    TempDir dir("sparse_bounds");
    GltfBuilder b;
    const float p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const uint8_t bad_index = 9;
    const float value[3] = {1, 1, 1};
    const int v = b.view(p, sizeof p);
    const int iv = b.view(&bad_index, 1);
    const int vv = b.view(value, 12);
    const int position =
        b.accessor(v, kFloat, 3, "VEC3",
                   R"(,"sparse":{"count":1,"indices":{"bufferView":)" + std::to_string(iv) +
                       R"(,"componentType":5121},"values":{"bufferView":)" + std::to_string(vv) + "}}");
    b.mesh("[" + primitive(position) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const fs::path path = b.write(dir.path(), "sparse");
    CHECK_THROWS_WITH_AS(load_gltf(path),
                         (path.string() + ": accessor 0 (POSITION of mesh 0 primitive 0) sparse index 0 is 9, "
                                          "outside the accessor's 3 elements")
                             .c_str(),
                         vplkit::Error);
}

TEST_CASE("an embedded image whose bufferView is outside the buffer is an error") {
    TempDir dir("image_view_bounds");
    GltfBuilder b;
    b.image_view(png(1, 1, {1, 2, 3, 4}));
    b.buffer_views.back() = R"({"buffer":0,"byteOffset":0,"byteLength":100000})";
    b.textures.push_back(R"({"source":0})");
    b.materials.push_back(R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})");
    b.mesh("[" + unit_quad(b, true, true, 0) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const fs::path path = b.write(dir.path(), "image");
    std::string message;
    try {
        (void)load_gltf(path);
    } catch (const vplkit::Error& e) {
        message = e.what();
    }
    INFO(message);
    CHECK(message.rfind(path.string() + ": bufferView 0 (used by image 0", 0) == 0);
    CHECK(message.find("0 + 100000") != std::string::npos);
}
