#pragma once
// One small glTF per feature of issue 19 (vertex colours, texture transforms, morph targets,
// skins, orthographic cameras, alpha masks, quantized attributes, and a file with features
// vplkit skips), each with a point light so `vplkit render` takes it as it is. Written by
// write_gltf_features (a ctest fixture, for the command-line tests) and used directly by the
// gltf suite; the CPU expectations the tests compare with are stated beside each builder.

#include "gltf_builder.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

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
GltfBuilder masked_quad(const std::string& alpha_mode = "MASK", float factor_alpha = 1.0f, bool textured = true);

// A quad plus a POINTS primitive, and extensionsUsed KHR_materials_clearcoat (not required): the
// loader skips both, so `vplkit render` warns twice and --strict fails.
GltfBuilder skipped_features();

}  // namespace gltf_features
