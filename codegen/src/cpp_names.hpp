// C++ spelling of shader things: scalar/vector/matrix type names, identifiers.
#pragma once

#include <cstdint>
#include <string>

#include "model.hpp"

namespace vplkit::codegen {

std::string scalar_cpp(Scalar s);                 // float, uint32_t, int64_t, ...
std::string vector_cpp(Scalar s, uint32_t size);  // vec3, uvec2, i64vec4, dvec2, ...
// The column stride a matrix gets in std140/std430 (vec2 columns: 2 components, vec3/vec4
// columns: 4 components). Matrices with this stride get the plain GLSL name (mat3); others
// carry their stride in the name (mat3_stride12 for a scalar-layout mat3).
uint32_t natural_matrix_stride(Scalar s, uint32_t rows);
std::string matrix_cpp(Scalar s, uint32_t columns, uint32_t rows, uint32_t stride);
// GLSL-like description of a member type, for error messages: "vec3[4] (stride 16)".
std::string describe_type(const MemberType& t);

bool is_cpp_keyword(const std::string& name);
bool is_identifier(const std::string& name);
// A GLSL name as a C++ identifier: keywords get a trailing underscore.
std::string cpp_identifier(const std::string& name);
// "sorted_keys" -> "SortedKeys", "inKeys" -> "InKeys".
std::string camel_case(const std::string& name);
// Names that types.hpp defines itself (vec3, mat4, padded, member_info, ...): shader
// structs must not use them.
bool is_builtin_type_name(const std::string& name);

}  // namespace vplkit::codegen
