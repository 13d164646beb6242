// The Pipeline wrapper of a compute shader's header (emit_pipeline.cpp): its declaration, and its
// definitions, which emit_shader_header places after the SPIR-V they use.
#pragma once

#include <string>

#include "emit.hpp"

namespace vplkit::codegen {

std::string emit_pipeline_declaration(const ShaderModel& shader, const EmitOptions& options);
std::string emit_pipeline_definitions(const ShaderModel& shader, const EmitOptions& options);

}  // namespace vplkit::codegen
