// types.hpp: the basic vector/matrix types, then every shader struct with its exact layout.
#include <set>

#include "cpp_names.hpp"
#include "emit.hpp"
#include "error.hpp"
#include "text.hpp"

namespace vplkit::codegen {

namespace {

const char* const kComponents[] = {"x", "y", "z", "w"};

std::string vector_struct(Scalar s, uint32_t n) {
    std::string fields;
    for (uint32_t i = 0; i < n; ++i) fields += std::string(i ? ", " : "") + kComponents[i];
    return "struct " + vector_cpp(s, n) + " { " + scalar_cpp(s) + " " + fields + "; };";
}

std::string matrix_struct(const MatrixShape& m) {
    const std::string column = vector_cpp(m.scalar, m.rows);
    const uint32_t column_size = scalar_size(m.scalar) * m.rows;
    const std::string element =
        m.stride == column_size ? column : "padded<" + column + ", " + std::to_string(m.stride) + ">";
    return "struct " + matrix_cpp(m.scalar, m.columns, m.rows, m.stride) + " { " + element + " columns[" +
           std::to_string(m.columns) + "]; };";
}

std::string basic_types(const TypeTable& types) {
    std::string out;
    out +=
        "// How a shader uses a binding (each header's kBindingAccess): SPIR-V NonWritable / NonReadable,\n"
        "// GLSL readonly / writeonly. Uniform buffers, samplers and sampled images are read.\n"
        "enum class Access : uint8_t { read, write, read_write };\n\n";
    out +=
        "// An element of an array whose stride is wider than the element (a vec3 in a std430\n"
        "// array, a float or vec2 in a std140 array), or a matrix column: the padding is a member.\n"
        "template <typename T, std::size_t Stride>\n"
        "struct padded {\n"
        "  T value;\n"
        "  uint8_t _pad[Stride - sizeof(T)];\n"
        "};\n\n";

    // Vectors: the 32-bit ones always (a foreign renderer may want them), others on demand.
    std::set<std::pair<Scalar, uint32_t>> vectors = types.vectors();
    for (Scalar s : {Scalar::Float32, Scalar::Int32, Scalar::UInt32}) {
        for (uint32_t n = 2; n <= 4; ++n) vectors.insert({s, n});
    }
    out +=
        "// Vectors: plain structs of their components, aligned like one component\n"
        "// (vec3 is 12 bytes, alignment 4), so a layout's padding is always explicit.\n";
    for (const auto& [s, n] : vectors) out += vector_struct(s, n) + "\n";
    for (const auto& [s, n] : vectors) {
        const std::string name = vector_cpp(s, n);
        out += "static_assert(sizeof(" + name + ") == " + std::to_string(n * scalar_size(s)) + " && alignof(" + name +
               ") == " + std::to_string(scalar_size(s)) + ");\n";
    }

    // Matrices: the float ones with std140/std430 column strides always, others on demand.
    std::set<MatrixShape> matrices = types.matrices();
    for (uint32_t c = 2; c <= 4; ++c) {
        for (uint32_t r = 2; r <= 4; ++r)
            matrices.insert({Scalar::Float32, c, r, natural_matrix_stride(Scalar::Float32, r)});
    }
    out +=
        "\n// Matrices: column-major, columns[i] is column i; a column is padded to the matrix's column\n"
        "// stride (16 bytes for vec3/vec4 columns in std140/std430; a _strideN suffix names any other).\n";
    for (const MatrixShape& m : matrices) out += matrix_struct(m) + "\n";
    for (const MatrixShape& m : matrices) {
        out += "static_assert(sizeof(" + matrix_cpp(m.scalar, m.columns, m.rows, m.stride) +
               ") == " + std::to_string(m.columns * m.stride) + ");\n";
    }

    out +=
        "\n// One row of a struct's kMembers table: each member as the SPIR-V declares it.\n"
        "struct member_info {\n"
        "  const char* name;\n"
        "  uint32_t offset;\n"
        "  uint32_t size;  // 0 for a runtime array\n"
        "};\n\n"
        "struct struct_info {\n"
        "  const char* name;\n"
        "  uint32_t size;  // sizeof; 0 for a block that holds only a runtime array\n"
        "  const member_info* members;\n"
        "  uint32_t member_count;\n"
        "};\n";
    return out;
}

std::string join(const std::vector<std::string>& items, const char* sep) {
    std::string out;
    for (const std::string& s : items) out += (out.empty() ? "" : sep) + s;
    return out;
}

std::string struct_definition(const ResolvedStruct& s, const TypeTable& types) {
    const Member* runtime = s.runtime_array();
    std::string header = "// " + s.name + ": ";
    if (runtime && s.members.size() == 1) {
        header += "a runtime array only (see the constants)";
    } else {
        header += std::to_string(s.size) + " bytes";
    }
    if (s.array_stride) header += ", array stride " + std::to_string(*s.array_stride);
    header += "; used by " + join(s.shaders, ", ") + "\n";

    CommentedLines body;
    CommentedLines asserts;
    uint32_t end = 0;
    int pad_index = 0;
    auto pad = [&](uint32_t to, const std::string& why) {
        if (to <= end) return;
        body.add("uint8_t _pad" + std::to_string(pad_index++) + "[" + std::to_string(to - end) + "];",
                 "offset " + std::to_string(end) + ", size " + std::to_string(to - end) + ": " + why);
        end = to;
    };
    std::string members_table;
    for (const Member& m : s.members) {
        const std::string id = cpp_identifier(m.name);
        const std::string where = "struct '" + s.name + "' member '" + m.name + "'";
        if (&m == runtime) {
            pad(m.offset, "padding up to the runtime array");
            members_table += "      {\"" + m.name + "\", " + std::to_string(m.offset) + ", 0},\n";
            continue;
        }
        pad(m.offset, "padding");
        const CppType c = types.cpp_type(m.type, 0, where);
        body.add(c.type + " " + id + c.suffix + ";",
                 "offset " + std::to_string(m.offset) + ", size " + std::to_string(c.size));
        asserts.add("static_assert(offsetof(" + s.name + ", " + id + ") == " + std::to_string(m.offset) + ");");
        members_table +=
            "      {\"" + m.name + "\", " + std::to_string(m.offset) + ", " + std::to_string(c.size) + "},\n";
        end = m.offset + c.size;
    }
    if (!runtime) pad(s.size, s.array_stride ? "padding up to the array stride" : "trailing padding");

    std::string out = header + "struct " + s.name + " {\n" + body.render("  ");
    if (runtime) {
        const std::string camel = camel_case(runtime->name);
        const CppType element =
            types.runtime_element(runtime->type, "struct '" + s.name + "' member '" + runtime->name + "'");
        out += std::string(body.empty() ? "" : "\n") + "  // " + runtime->name + "[]: runtime array, " +
               std::to_string(element.size) + " bytes per element\n";
        out += "  using " + camel + "Element = " + element.type + element.suffix + ";\n";
        out += "  static constexpr uint32_t k" + camel + "Offset = " + std::to_string(runtime->offset) + ";\n";
        out += "  static constexpr uint32_t k" + camel +
               "Stride = " + std::to_string(runtime->type.dims.front().stride) + ";\n";
        asserts.add("static_assert(sizeof(" + s.name + "::" + camel + "Element) == " + s.name + "::k" + camel +
                    "Stride);");
    }
    out += "\n  static constexpr member_info kMembers[] = {\n" + members_table + "  };\n};\n";
    if (s.size != 0) out += "static_assert(sizeof(" + s.name + ") == " + std::to_string(s.size) + ");\n";
    out += asserts.render("");
    return out;
}

}  // namespace

std::string emit_types_header(const TypeTable& types, const EmitOptions& options) {
    std::string out =
        "// Generated by vplkit-codegen. Do not edit: edit the shaders.\n"
        "//\n"
        "// Host mirrors of the structs the shaders of this library share with the host. Each struct\n"
        "// reproduces the layout its SPIR-V declares (std140, std430 or scalar) byte for byte:\n"
        "// every gap is an explicit _pad member, every member's comment gives its offset and size,\n"
        "// and static_asserts check each offset and each size.\n"
        "#pragma once\n\n"
        "#include <cstddef>\n"
        "#include <cstdint>\n\n"
        "namespace " +
        options.cpp_namespace + " {\n\n";
    out += basic_types(types);
    for (const ResolvedStruct& s : types.structs()) out += "\n" + struct_definition(s, types);

    out += "\n// Every struct above, for tests and tools that walk the layouts.\n";
    if (types.structs().empty()) {
        out += "inline constexpr const struct_info* kStructs = nullptr;\ninline constexpr uint32_t kStructCount = 0;\n";
    } else {
        out += "inline constexpr struct_info kStructs[] = {\n";
        for (const ResolvedStruct& s : types.structs()) {
            out += "    {\"" + s.name + "\", " + (s.size ? "sizeof(" + s.name + ")" : std::string("0")) + ", " +
                   s.name + "::kMembers, " + std::to_string(s.members.size()) + "},\n";
        }
        out += "};\ninline constexpr uint32_t kStructCount = " + std::to_string(types.structs().size()) + ";\n";
    }
    out += "\n}  // namespace " + options.cpp_namespace + "\n";
    return out;
}

}  // namespace vplkit::codegen
