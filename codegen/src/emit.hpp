// Model -> C++ header text. Pure functions: no file access, so a failure anywhere leaves
// nothing half-written (main writes files only once every text is ready).
#pragma once

#include <string>
#include <vector>

#include "layout_check.hpp"
#include "model.hpp"

namespace vplkit::codegen {

struct EmitOptions {
    std::string cpp_namespace;  // e.g. vplkit::shaders
};

std::string emit_types_header(const TypeTable& types, const EmitOptions& options);
std::string emit_shader_header(const ShaderModel& shader, const EmitOptions& options);

}  // namespace vplkit::codegen
