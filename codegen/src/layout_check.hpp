// Cross-shader struct merge and the C++ layout of every struct.
//
// All shaders of a library share one types.hpp, so a struct name means one layout.
// build_type_table() merges the structs found in every shader (and the several copies
// glslang may make inside one shader), fails on the first disagreement, orders the structs
// so that each comes after the structs it contains, and decides each struct's C++ size:
// the array stride where the struct is an array element (so a std::vector<Vpl> matches a
// `Vpl vpls[]` buffer), otherwise the end of its last member.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "model.hpp"

namespace vplkit::codegen {

// A member's type as C++ declares it: `type name suffix;`, e.g. `padded<vec3, 16> dirs[4];`.
struct CppType {
    std::string type;
    std::string suffix;  // C array dimensions
    uint32_t size = 0;
    uint32_t align = 1;
};

struct ResolvedStruct {
    std::string name;
    std::vector<Member> members;
    std::vector<std::string> shaders;  // every shader that uses it, sorted
    uint32_t size = 0;                 // sizeof in C++; 0: the block holds only a runtime array
    uint32_t align = 1;
    std::optional<uint32_t> array_stride;  // set if some shader uses it as an array element

    const Member* runtime_array() const {
        return !members.empty() && members.back().type.is_runtime_array() ? &members.back() : nullptr;
    }
};

struct MatrixShape {
    Scalar scalar;
    uint32_t columns, rows, stride;
    auto operator<=>(const MatrixShape&) const = default;
};

class TypeTable {
public:
    const std::vector<ResolvedStruct>& structs() const { return structs_; }
    const ResolvedStruct& get(const std::string& name) const;
    bool contains(const std::string& name) const { return index_.count(name) != 0; }

    // The C++ declaration of a member type, skipping its first `skip_dims` array dimensions
    // (1 for the element of a runtime array). Throws Error (mentioning `where`) if C++
    // cannot reproduce the declared strides.
    CppType cpp_type(const MemberType& t, size_t skip_dims, const std::string& where) const;
    // The element of a runtime array, padded to the array stride: one element of a host-side
    // std::vector that mirrors the buffer.
    CppType runtime_element(const MemberType& t, const std::string& where) const;

    // Matrix and vector types beyond the always-present ones (vec*, ivec*, uvec*, and the
    // float matrices with std140/std430 strides), needed by some member.
    const std::set<MatrixShape>& matrices() const { return matrices_; }
    const std::set<std::pair<Scalar, uint32_t>>& vectors() const { return vectors_; }

private:
    friend TypeTable build_type_table(const std::vector<ShaderModel>& shaders);
    std::vector<ResolvedStruct> structs_;
    std::map<std::string, size_t> index_;
    std::set<MatrixShape> matrices_;
    std::set<std::pair<Scalar, uint32_t>> vectors_;
};

TypeTable build_type_table(const std::vector<ShaderModel>& shaders);

}  // namespace vplkit::codegen
