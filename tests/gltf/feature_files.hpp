#pragma once
// One small glTF per feature a user's file may use (vertex colours, texture transforms, morph targets,
// skins, orthographic cameras, alpha masks, quantized attributes, an animated scene from
// animation_files.hpp, and a file with features vplkit skips), each with a point light so
// `vplkit render` takes it as it is. Written by write_gltf_features (a ctest fixture, for the
// command-line tests) and used directly by the gltf suite; the CPU expectations the tests
// compare with are stated beside each builder.

#include "gltf_builder.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace gltf_features {

using scene_test::GltfBuilder;

struct FeatureFile {
    std::string name;  // the file is <name>.gltf (buffer embedded)
    std::function<GltfBuilder()> build;
};

// Every feature file, in a fixed order.
const std::vector<FeatureFile>& feature_files();

// Writes every feature file into `dir` (created if missing); returns the paths.
std::vector<std::filesystem::path> write_all(const std::filesystem::path& dir);

// The builders, for tests that load one file.

// A quad (unit_quad) whose corners carry COLOR_0 red, green, blue, white as `component_type`
// (kFloat, or normalized kUnsignedByte / kUnsignedShort), RGB or RGBA (`rgba`: alpha 1), under a
// material with base colour factor (0.5, 0.5, 0.5, 1). Expected albedo at a corner:
// 0.5 x its colour.
GltfBuilder vertex_colors(int component_type = scene_test::kFloat, bool rgba = false);

// The unit quad (UVs (x, 1 - y)) under a material of `alpha_mode` ("MASK", "BLEND", "OPAQUE"),
// cutoff 0.5, base colour factor alpha `factor_alpha`, and (when `textured`) a 4 x 1 base colour
// texture whose alpha is 0, 255, 0, 255 left to right (nearest, clamp). Expected for MASK: a ray
// through x in texel 0 or 2 passes, through texel 1 or 3 is blocked; BLEND is MASK at 0.5.
// `u_offset` != 0 adds KHR_texture_transform with that offset along u: the texel at x is then the
// one at x + u_offset (clamped).
GltfBuilder masked_quad(const std::string& alpha_mode = "MASK", float factor_alpha = 1.0f, bool textured = true,
                        float u_offset = 0.0f);

// The 4 x 1 texture of textured_quad: texels red, green, blue, white (opaque, sRGB 0 or 255, so
// linear 0 or 1), left to right.
inline constexpr float kStripTexels[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};

// How textured_quad reads its texture.
struct TexturedQuad {
    int info_tex_coord = 0;  // baseColorTexture.texCoord
    bool transform = false;  // add KHR_texture_transform with the members below
    float offset[2] = {0.0f, 0.0f};
    float rotation = 0.0f;
    float scale[2] = {1.0f, 1.0f};
    int transform_tex_coord = -1;  // the extension's texCoord override (-1: none)
    int wrap_s = 33071;            // CLAMP_TO_EDGE; 10497 REPEAT, 33648 MIRRORED_REPEAT
};

// The unit quad with kStripTexels as its base colour texture (nearest filtering, wrapT clamp),
// metallic 0. The UVs (x, 1 - y) are TEXCOORD_0 when the texture reads set 0 and TEXCOORD_1
// when it reads set 1 (then TEXCOORD_0 is (0.9, 0.5) everywhere: a wrong set shows white).
// Expected albedo at (x, y): the texel under the UV transform of (x, 1 - y), wrapped.
GltfBuilder textured_quad(const TexturedQuad& options);

// The unit quad with two morph targets: target 0 moves vertices 1 and 2 by (0, 0, 2) through a
// sparse accessor (no bufferView) and turns every normal by (1, 0, -1); target 1 moves every
// vertex by (1, 0, 0). The mesh's weights are (0.5, 0); `node_weights` (when not empty) are the
// node's, which take precedence. Expected: position + sum w_t d_t, normal normalized likewise.
GltfBuilder morph_quad(const std::vector<float>& node_weights = {});

// The unit quad skinned to two joints: node "hip" (joint 0, at the origin) and its child "arm"
// (joint 1, translation (0.5, 0, 0), rotated `arm_degrees` about +Y; inverse bind matrix
// T(-0.5, 0, 0): bound unrotated). Vertices 0 and 3 follow the hip, vertex 1 the arm, vertex 2
// both at 0.5. The mesh node has translation (5, 5, 5), which skinning ignores. Joints as
// UNSIGNED_BYTE or UNSIGNED_SHORT (`short_joints`), weights as FLOAT or normalized UNSIGNED_BYTE.
// `mirrored`: the hip has scale (-1, 1, 1) (its inverse bind matrix stays the identity), so the
// whole pose is mirrored in x.
GltfBuilder skinned_quad(float arm_degrees, bool short_joints = false, bool mirrored = false);

// The unit quad seen by camera 0, perspective from (0.5, 0.5, 2), and camera 1, orthographic from
// (0.5, 0.5, 1) looking down -Z with ymag 0.625 (xmag 0.625), znear 0.1, zfar 10.
GltfBuilder two_cameras();

// The unit quad with KHR_mesh_quantization: positions as `position_type` (kUnsignedShort
// normalized: q = p x 65535, node scale 1; kShort: q = p x 1000, unnormalized, node scale
// 0.001), normals as normalized BYTE, UVs as normalized UNSIGNED_BYTE. Expected: the float quad.
// `declare` false leaves the extension out of extensionsUsed (the loader must refuse the file).
GltfBuilder quantized_quad(int position_type, bool declare = true);

// A quad plus a POINTS primitive, an animation (a translation of the quad's node, skipped when
// no time is given) and extensionsUsed KHR_materials_clearcoat (not required): the loader skips
// all three, so `vplkit render` warns three times (each once) and --strict fails.
GltfBuilder skipped_features();

}  // namespace gltf_features
