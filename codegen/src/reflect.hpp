// SPIR-V -> ShaderModel, with SPIRV-Cross. Rejects (with an Error naming the shader and
// the offending binding/struct/member) whatever the generated headers cannot express.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model.hpp"

namespace vplkit::codegen {

ShaderModel reflect_shader(const std::string& name, std::vector<uint32_t> words);

// Reads a .spv file into words; throws Error if it cannot be read or is not SPIR-V.
std::vector<uint32_t> read_spirv_file(const std::string& path);

}  // namespace vplkit::codegen
