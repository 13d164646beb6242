#include "cpp_names.hpp"

#include <algorithm>
#include <iterator>
#include <cctype>
#include <string_view>

namespace vplkit::codegen {

std::string scalar_cpp(Scalar s) {
    switch (s) {
        case Scalar::Int8:
            return "int8_t";
        case Scalar::UInt8:
            return "uint8_t";
        case Scalar::Int16:
            return "int16_t";
        case Scalar::UInt16:
            return "uint16_t";
        case Scalar::Int32:
            return "int32_t";
        case Scalar::UInt32:
            return "uint32_t";
        case Scalar::Int64:
            return "int64_t";
        case Scalar::UInt64:
            return "uint64_t";
        case Scalar::Float32:
            return "float";
        case Scalar::Float64:
            return "double";
        case Scalar::DeviceAddress:
            return "uint64_t";
    }
    return "uint32_t";
}

namespace {

// GLSL's prefix for vectors and matrices of a component type.
std::string glsl_prefix(Scalar s) {
    switch (s) {
        case Scalar::Int8:
            return "i8";
        case Scalar::UInt8:
            return "u8";
        case Scalar::Int16:
            return "i16";
        case Scalar::UInt16:
            return "u16";
        case Scalar::Int32:
            return "i";
        case Scalar::UInt32:
            return "u";
        case Scalar::Int64:
            return "i64";
        case Scalar::UInt64:
        case Scalar::DeviceAddress:
            return "u64";
        case Scalar::Float32:
            return "";
        case Scalar::Float64:
            return "d";
    }
    return "";
}

}  // namespace

std::string vector_cpp(Scalar s, uint32_t size) {
    return glsl_prefix(s) + "vec" + std::to_string(size);
}

uint32_t natural_matrix_stride(Scalar s, uint32_t rows) {
    return scalar_size(s) * (rows == 2 ? 2 : 4);
}

std::string matrix_cpp(Scalar s, uint32_t columns, uint32_t rows, uint32_t stride) {
    std::string name = glsl_prefix(s) + "mat" + std::to_string(columns);
    if (columns != rows) name += "x" + std::to_string(rows);
    if (stride != natural_matrix_stride(s, rows)) name += "_stride" + std::to_string(stride);
    return name;
}

std::string describe_type(const MemberType& t) {
    std::string text;
    switch (t.kind) {
        case MemberType::Kind::Scalar:
            text = scalar_cpp(t.scalar);
            break;
        case MemberType::Kind::Vector:
            text = vector_cpp(t.scalar, t.rows);
            break;
        case MemberType::Kind::Matrix:
            text = matrix_cpp(t.scalar, t.columns, t.rows, natural_matrix_stride(t.scalar, t.rows)) +
                   " (column stride " + std::to_string(t.matrix_stride) + ")";
            break;
        case MemberType::Kind::Struct:
            text = t.struct_name;
            break;
    }
    for (const ArrayDim& d : t.dims) text += d.count ? "[" + std::to_string(d.count) + "]" : "[]";
    if (!t.dims.empty()) {
        text += " (stride";
        for (const ArrayDim& d : t.dims) text += " " + std::to_string(d.stride);
        text += ")";
    }
    return text;
}

bool is_cpp_keyword(const std::string& name) {
    static constexpr std::string_view kKeywords[] = {
        "alignas",     "alignof",   "and",        "and_eq",    "asm",      "auto",         "bitand",
        "bitor",       "bool",      "break",      "case",      "catch",    "char",         "char8_t",
        "char16_t",    "char32_t",  "class",      "compl",     "concept",  "const",        "consteval",
        "constexpr",   "constinit", "const_cast", "continue",  "co_await", "co_return",    "co_yield",
        "decltype",    "default",   "delete",     "do",        "double",   "dynamic_cast", "else",
        "enum",        "explicit",  "export",     "extern",    "false",    "float",        "for",
        "friend",      "goto",      "if",         "inline",    "int",      "long",         "mutable",
        "namespace",   "new",       "noexcept",   "not",       "not_eq",   "nullptr",      "operator",
        "or",          "or_eq",     "private",    "protected", "public",   "register",     "reinterpret_cast",
        "requires",    "return",    "short",      "signed",    "sizeof",   "static",       "static_assert",
        "static_cast", "struct",    "switch",     "template",  "this",     "thread_local", "throw",
        "true",        "try",       "typedef",    "typeid",    "typename", "union",        "unsigned",
        "using",       "virtual",   "void",       "volatile",  "wchar_t",  "while",        "xor",
        "xor_eq",      "final",     "override",   "import",    "module"};
    return std::find(std::begin(kKeywords), std::end(kKeywords), name) != std::end(kKeywords);
}

bool is_identifier(const std::string& name) {
    if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return false;
    return std::all_of(name.begin(), name.end(),
                       [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

std::string cpp_identifier(const std::string& name) {
    return is_cpp_keyword(name) ? name + "_" : name;
}

std::string camel_case(const std::string& name) {
    std::string out;
    bool upper = true;
    for (char c : name) {
        if (c == '_') {
            upper = true;
            continue;
        }
        out += upper ? char(std::toupper(static_cast<unsigned char>(c))) : c;
        upper = false;
    }
    return out;
}

bool is_builtin_type_name(const std::string& name) {
    if (name == "padded" || name == "member_info" || name == "struct_info" || name == "kStructs") {
        return true;
    }
    // vecN / matN / matNxM with any GLSL prefix, and the C++ scalar names.
    for (const char* prefix : {"", "i", "u", "d", "i8", "u8", "i16", "u16", "i64", "u64"}) {
        const std::string p = prefix;
        if (name.starts_with(p + "vec") || name.starts_with(p + "mat")) {
            const std::string rest = name.substr(p.size() + 3);
            if (!rest.empty() && std::isdigit(static_cast<unsigned char>(rest[0]))) return true;
        }
    }
    for (Scalar s : {Scalar::Int8, Scalar::UInt8, Scalar::Int16, Scalar::UInt16, Scalar::Int32, Scalar::UInt32,
                     Scalar::Int64, Scalar::UInt64}) {
        if (name == scalar_cpp(s)) return true;
    }
    return false;
}

}  // namespace vplkit::codegen
