// In-memory model of what a shader exposes to the host: structs with their exact SPIR-V
// layout, descriptor bindings, the push-constant block, specialization constants and the
// workgroup size. reflect.cpp fills it from SPIR-V; layout_check.cpp merges the structs of
// all shaders; emit_*.cpp turn it into C++. Nothing here depends on SPIRV-Cross.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vplkit::codegen {

// Component types that can appear in a block. Bool cannot: glslang stores a GLSL `bool`
// block member as a 32-bit uint, so it reaches us (and the host) as UInt32.
enum class Scalar {
    Int8,
    UInt8,
    Int16,
    UInt16,
    Int32,
    UInt32,
    Int64,
    UInt64,
    Float32,
    Float64,
    DeviceAddress,  // a GL_EXT_buffer_reference pointer: 64-bit VkDeviceAddress on the host
};

inline uint32_t scalar_size(Scalar s) {
    switch (s) {
        case Scalar::Int8:
        case Scalar::UInt8:
            return 1;
        case Scalar::Int16:
        case Scalar::UInt16:
            return 2;
        case Scalar::Int32:
        case Scalar::UInt32:
        case Scalar::Float32:
            return 4;
        case Scalar::Int64:
        case Scalar::UInt64:
        case Scalar::Float64:
        case Scalar::DeviceAddress:
            return 8;
    }
    return 4;
}

struct ArrayDim {
    uint32_t count = 0;   // 0: runtime-sized (only allowed as the outermost dimension of the last member)
    uint32_t stride = 0;  // ArrayStride decoration
    bool operator==(const ArrayDim&) const = default;
};

// The type of one struct member, exactly as the SPIR-V declares it.
struct MemberType {
    enum class Kind { Scalar, Vector, Matrix, Struct };
    Kind kind = Kind::Scalar;
    Scalar scalar = Scalar::UInt32;  // component type (Scalar, Vector, Matrix)
    uint32_t rows = 1;               // vector size, or the number of rows of a matrix
    uint32_t columns = 1;            // matrices only
    uint32_t matrix_stride = 0;      // matrices only: bytes between columns (MatrixStride)
    std::string struct_name;         // Kind::Struct only
    std::vector<ArrayDim> dims;      // array dimensions, outermost first; empty if not an array
    bool operator==(const MemberType&) const = default;

    bool is_runtime_array() const { return !dims.empty() && dims.front().count == 0; }
};

struct Member {
    std::string name;
    uint32_t offset = 0;
    MemberType type;
};

// One struct type as found in one shader. A shader may declare the same struct several
// times (glslang makes one SPIR-V type per block layout); layout_check merges them.
struct StructLayout {
    std::string name;
    std::string shader;  // the shader it was found in, for messages
    std::vector<Member> members;
};

// A struct used as an array element: the stride decides the struct's trailing padding.
struct ArrayUse {
    std::string struct_name;
    uint32_t stride = 0;
    std::string shader;
    std::string where;  // "member 'items' of struct 'VplBuffer'", for messages
};

enum class DescriptorKind {
    UniformBuffer,
    StorageBuffer,
    CombinedImageSampler,
    SampledImage,
    Sampler,
    StorageImage,
    InputAttachment,
};

// How a shader may use a binding, from SPIR-V's NonWritable / NonReadable decorations (GLSL
// readonly / writeonly): what a frame graph needs to place barriers. Uniform buffers, samplers and
// sampled images are read.
enum class Access { Read, Write, ReadWrite };

struct Binding {
    std::string name;  // GLSL instance name (the block type name if the block has none)
    uint32_t binding = 0;
    uint32_t count = 1;     // descriptor count: > 1 for a descriptor array
    bool is_array = false;  // declared as an array (even of size 1): the Bindings field is a std::array
    DescriptorKind kind = DescriptorKind::StorageBuffer;
    Access access = Access::Read;
    std::string block_type;  // buffers only: the block's struct name
};

struct SpecConstant {
    enum class Type { Bool, Int32, UInt32, Float32, Int64, UInt64, Float64 };
    std::string name;  // GLSL name; local_size_{x,y,z} for unnamed workgroup-size constants
    uint32_t constant_id = 0;
    Type type = Type::UInt32;
    uint64_t default_bits = 0;  // the default value's bits (low 32 bits for 32-bit types)
};

enum class Stage { Vertex, Fragment, Compute };

struct PushBlock {
    std::string struct_name;
    uint32_t offset = 0;  // first member's offset (usually 0)
    uint32_t size = 0;    // from offset to the end of the last member
};

struct ShaderModel {
    std::string name;
    Stage stage = Stage::Compute;
    std::string entry_point;
    std::vector<uint32_t> words;
    std::vector<Binding> bindings;  // sorted by binding number
    std::optional<PushBlock> push;
    std::vector<SpecConstant> spec_constants;  // sorted by constant_id, one per id
    // Compute only: the workgroup size, defaults resolved, and for each dimension the
    // constant_id that specializes it (local_size_*_id), if any.
    std::array<uint32_t, 3> workgroup_size = {1, 1, 1};
    std::array<std::optional<uint32_t>, 3> workgroup_size_ids;
    // Compute only: the shader takes its index from vplkit/dispatch.glsl (it calls
    // linear_workgroup_index()), so dispatch() may fold a 1D grid of more than 65,535 workgroups
    // into rows.
    bool folds_grid = false;
    std::vector<StructLayout> structs;  // every struct reached from a block, maybe repeated
    std::vector<ArrayUse> array_uses;
};

}  // namespace vplkit::codegen
