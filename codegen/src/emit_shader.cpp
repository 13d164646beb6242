// <name>.hpp: one shader's SPIR-V, descriptor layout, push constants, specialization
// constants and, for a compute shader, the Pipeline wrapper (emit_pipeline.cpp).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>

#include "cpp_names.hpp"
#include "emit.hpp"
#include "emit_pipeline.hpp"
#include "error.hpp"
#include "text.hpp"

namespace vplkit::codegen {

namespace {

const char* stage_flag(Stage s) {
    switch (s) {
        case Stage::Vertex:
            return "VK_SHADER_STAGE_VERTEX_BIT";
        case Stage::Fragment:
            return "VK_SHADER_STAGE_FRAGMENT_BIT";
        case Stage::Compute:
            return "VK_SHADER_STAGE_COMPUTE_BIT";
    }
    return "";
}

const char* stage_word(Stage s) {
    switch (s) {
        case Stage::Vertex:
            return "vertex";
        case Stage::Fragment:
            return "fragment";
        case Stage::Compute:
            return "compute";
    }
    return "";
}

const char* descriptor_type(DescriptorKind k) {
    switch (k) {
        case DescriptorKind::UniformBuffer:
            return "VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER";
        case DescriptorKind::StorageBuffer:
            return "VK_DESCRIPTOR_TYPE_STORAGE_BUFFER";
        case DescriptorKind::CombinedImageSampler:
            return "VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER";
        case DescriptorKind::SampledImage:
            return "VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE";
        case DescriptorKind::Sampler:
            return "VK_DESCRIPTOR_TYPE_SAMPLER";
        case DescriptorKind::StorageImage:
            return "VK_DESCRIPTOR_TYPE_STORAGE_IMAGE";
        case DescriptorKind::InputAttachment:
            return "VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT";
    }
    return "";
}

std::string descriptor_words(const Binding& b) {
    switch (b.kind) {
        case DescriptorKind::UniformBuffer:
            return "uniform buffer " + b.block_type;
        case DescriptorKind::StorageBuffer:
            return "storage buffer " + b.block_type;
        case DescriptorKind::CombinedImageSampler:
            return "combined image sampler";
        case DescriptorKind::SampledImage:
            return "sampled image";
        case DescriptorKind::Sampler:
            return "sampler";
        case DescriptorKind::StorageImage:
            return "storage image";
        case DescriptorKind::InputAttachment:
            return "input attachment";
    }
    return "";
}

const char* access_cpp(Access a) {
    switch (a) {
        case Access::Read:
            return "Access::read";
        case Access::Write:
            return "Access::write";
        case Access::ReadWrite:
            return "Access::read_write";
    }
    return "";
}

bool is_buffer(DescriptorKind k) {
    return k == DescriptorKind::UniformBuffer || k == DescriptorKind::StorageBuffer;
}

std::string binding_field_type(const Binding& b) {
    const std::string info = is_buffer(b.kind) ? "VkDescriptorBufferInfo" : "VkDescriptorImageInfo";
    return b.is_array ? "std::array<" + info + ", " + std::to_string(b.count) + ">" : info;
}

std::string spec_cpp_type(SpecConstant::Type t) {
    switch (t) {
        case SpecConstant::Type::Bool:
            return "VkBool32";
        case SpecConstant::Type::Int32:
            return "int32_t";
        case SpecConstant::Type::UInt32:
            return "uint32_t";
        case SpecConstant::Type::Float32:
            return "float";
        case SpecConstant::Type::Int64:
            return "int64_t";
        case SpecConstant::Type::UInt64:
            return "uint64_t";
        case SpecConstant::Type::Float64:
            return "double";
    }
    return "";
}

uint32_t spec_size(SpecConstant::Type t) {
    return t == SpecConstant::Type::Int64 || t == SpecConstant::Type::UInt64 || t == SpecConstant::Type::Float64 ? 8
                                                                                                                 : 4;
}

template <typename F>
std::string float_literal(F value, const char* suffix, const std::string& what) {
    if (!std::isfinite(value)) throw Error(what + " has a non-finite default value");
    char buf[64];
    const auto result = std::to_chars(buf, buf + sizeof(buf), value);  // shortest text that round-trips
    std::string text(buf, result.ptr);
    if (text.find_first_of(".e") == std::string::npos) text += ".0";
    return text + suffix;
}

std::string spec_default(const SpecConstant& c, const std::string& what) {
    switch (c.type) {
        case SpecConstant::Type::Bool:
            return c.default_bits ? "VK_TRUE" : "VK_FALSE";
        case SpecConstant::Type::Int32: {
            const int32_t v = int32_t(uint32_t(c.default_bits));
            return v == INT32_MIN ? "INT32_MIN" : std::to_string(v);
        }
        case SpecConstant::Type::UInt32:
            return std::to_string(uint32_t(c.default_bits));
        case SpecConstant::Type::Int64: {
            const int64_t v = int64_t(c.default_bits);
            return v == INT64_MIN ? "INT64_MIN" : std::to_string(v);
        }
        case SpecConstant::Type::UInt64:
            return std::to_string(c.default_bits) + "u";
        case SpecConstant::Type::Float32: {
            float f;
            const uint32_t bits = uint32_t(c.default_bits);
            std::memcpy(&f, &bits, 4);
            return float_literal(f, "f", what);
        }
        case SpecConstant::Type::Float64: {
            double d;
            std::memcpy(&d, &c.default_bits, 8);
            return float_literal(d, "", what);
        }
    }
    return "0";
}

class ShaderEmitter {
public:
    ShaderEmitter(const ShaderModel& shader, const EmitOptions& options) : s_(shader), options_(options) {}

    std::string run() {
        check_names();
        std::string out = preamble();
        out += "namespace " + options_.cpp_namespace + "::" + s_.name + " {\n\n";
        out += "inline constexpr VkShaderStageFlagBits kStage = " + std::string(stage_flag(s_.stage)) + ";\n";
        out += "inline constexpr const char* kEntryPoint = \"" + s_.entry_point + "\";\n";
        out += descriptors();
        out += push_constants();
        if (s_.stage == Stage::Compute) out += workgroup();
        out += spec();
        out += bindings();
        out += descriptor_writes();
        if (s_.stage == Stage::Compute) out += emit_pipeline_declaration(s_, options_);
        out += spirv();
        out += spec_definitions();
        out += module_type();
        if (s_.stage == Stage::Compute) out += emit_pipeline_definitions(s_, options_);
        out += "\n}  // namespace " + options_.cpp_namespace + "::" + s_.name + "\n";
        return out;
    }

private:
    [[noreturn]] void fail(const std::string& what) const { throw Error("shader '" + s_.name + "': " + what); }

    // The names generated inside this header must be distinct.
    void check_names() const {
        std::set<std::string> constants, fields;
        for (const Binding& b : s_.bindings) {
            if (!constants.insert("kBinding" + camel_case(b.name)).second) {
                fail("bindings named like '" + b.name + "' give the same constant kBinding" + camel_case(b.name) +
                     "; rename one");
            }
            fields.insert(cpp_identifier(b.name));
        }
        std::set<std::string> spec_names = {"info", "workgroup_size"};
        for (const SpecConstant& c : s_.spec_constants) {
            if (!is_identifier(c.name) || !spec_names.insert(cpp_identifier(c.name)).second) {
                fail("specialization constant '" + c.name + "' clashes with another name in Spec; rename it");
            }
        }
    }

    std::string preamble() const {
        std::string out = "// Generated by vplkit-codegen from the " + std::string(stage_word(s_.stage)) + " shader '" +
                          s_.name + "'. Do not edit: edit the shader.\n//\n";
        out +=
            "// Everything needed to use this shader without the vplkit runtime: its SPIR-V, its\n"
            "// descriptor set 0 layout (a push-descriptor layout), push-constant range,\n"
            "// specialization constants";
        out += s_.stage == Stage::Compute ? ", workgroup size and a pipeline wrapper.\n" : ".\n";
        out += "// Structs shared with the host are in types.hpp.\n";
        out += "#pragma once\n\n#include <array>\n#include <cstddef>\n#include <cstdint>\n";
        // Compute: Pipeline::groups() throws std::length_error for a grid no device must take.
        if (s_.stage == Stage::Compute) out += "#include <stdexcept>\n#include <string>\n";
        out += "\n#include <vulkan/vulkan.h>\n\n";
        out += "#include \"types.hpp\"\n\n";
        return out;
    }

    std::string descriptors() const {
        std::string out =
            "\n// Descriptor set 0: the only set; its layout is a push-descriptor layout\n"
            "// (VK_KHR_push_descriptor), so there is no descriptor pool to manage.\n";
        if (s_.bindings.empty()) {
            out += "// This shader has no descriptors.\n";
            out += "inline constexpr std::array<VkDescriptorSetLayoutBinding, 0> kSetLayoutBindings = {};\n";
            out += "inline constexpr std::array<Access, 0> kBindingAccess = {};\n";
            out += "inline constexpr std::array<const char*, 0> kBindingNames = {};\n";
            return out;
        }
        CommentedLines lines;
        for (const Binding& b : s_.bindings) {
            std::string comment = descriptor_words(b);
            if (b.is_array) comment += ", array of " + std::to_string(b.count);
            comment += b.access == Access::Read    ? ", read"
                       : b.access == Access::Write ? ", written"
                                                   : ", read and written";
            lines.add(
                "inline constexpr uint32_t kBinding" + camel_case(b.name) + " = " + std::to_string(b.binding) + ";",
                comment);
        }
        out += lines.render("");
        out += "inline constexpr VkDescriptorSetLayoutBinding kSetLayoutBindings[] = {\n";
        for (const Binding& b : s_.bindings) {
            out += "    {kBinding" + camel_case(b.name) + ", " + descriptor_type(b.kind) + ", " +
                   std::to_string(b.count) + ", kStage, nullptr},\n";
        }
        out += "};\n";
        out +=
            "// How the shader uses each binding of kSetLayoutBindings, in the same order (readonly /\n"
            "// writeonly in the GLSL): the accesses a caller's barriers must cover.\n";
        out += "inline constexpr Access kBindingAccess[] = {\n";
        for (const Binding& b : s_.bindings)
            out += "    " + std::string(access_cpp(b.access)) + ",  // " + b.name + "\n";
        out += "};\n";
        out += "// Each binding's name in the GLSL, in the same order.\n";
        out += "inline constexpr const char* kBindingNames[] = {";
        for (size_t i = 0; i < s_.bindings.size(); ++i) out += (i ? ", \"" : "\"") + s_.bindings[i].name + "\"";
        out += "};\n";
        return out;
    }

    std::string push_constants() const {
        if (!s_.push) return "\n// No push constants.\n";
        return "\n// Push constants: the " + s_.push->struct_name +
               " block (types.hpp).\n"
               "using Push = " +
               s_.push->struct_name +
               ";\n"
               "inline constexpr VkPushConstantRange kPushConstantRange = {kStage, " +
               std::to_string(s_.push->offset) + ", " + std::to_string(s_.push->size) + "};\n";
    }

    std::string workgroup() const {
        std::string out =
            "\n// Workgroup size with the specialization constants at their defaults;\n"
            "// Spec::workgroup_size() gives it for other values.\n";
        out += "inline constexpr uint32_t kWorkgroupSize[3] = {" + std::to_string(s_.workgroup_size[0]) + ", " +
               std::to_string(s_.workgroup_size[1]) + ", " + std::to_string(s_.workgroup_size[2]) + "};\n";
        out +=
            "\n// Workgroups per dimension that every device takes (maxComputeWorkGroupCount's minimum).\n"
            "inline constexpr uint32_t kMaxGroupsPerDimension = 65535;\n";
        out += s_.folds_grid
                   ? "// The shader takes its index from vplkit/dispatch.glsl (linear_thread_index): dispatch()\n"
                     "// folds a 1D grid of more than kMaxGroupsPerDimension workgroups into rows.\n"
                   : "// The shader does not take its index from vplkit/dispatch.glsl: dispatch() cannot fold a\n"
                     "// grid of more than kMaxGroupsPerDimension workgroups in a dimension (it throws).\n";
        out += std::string("inline constexpr bool kFoldsGrid = ") + (s_.folds_grid ? "true" : "false") + ";\n";
        return out;
    }

    const SpecConstant* spec_by_id(uint32_t id) const {
        for (const SpecConstant& c : s_.spec_constants) {
            if (c.constant_id == id) return &c;
        }
        return nullptr;
    }

    std::string spec() {
        std::string out =
            s_.spec_constants.empty()
                ? "\n// Specialization constants: none; info() is empty.\n"
                : "\n// Specialization constants, defaults from the shader. The members are the specialization\n"
                  "// data itself (standard layout, no implicit padding): info() points into this Spec,\n"
                  "// so keep it alive until the pipeline is created.\n";
        out += "struct Spec {\n";
        CommentedLines lines;
        uint32_t offset = 0;
        int pad_index = 0;
        for (const SpecConstant& c : s_.spec_constants) {
            const uint32_t size = spec_size(c.type);
            if (offset % size != 0) {
                lines.add("uint32_t _pad" + std::to_string(pad_index++) + " = 0;",
                          "keeps the next member 8-byte aligned");
                offset += 4;
            }
            std::string comment = "constant_id " + std::to_string(c.constant_id);
            for (int d = 0; d < 3; ++d) {
                if (s_.workgroup_size_ids[d] == c.constant_id)
                    comment += std::string(", local_size_") + "xyz"[d] + "_id";
            }
            lines.add(spec_cpp_type(c.type) + " " + cpp_identifier(c.name) + " = " +
                          spec_default(c, "specialization constant '" + c.name + "'") + ";",
                      comment);
            offset += size;
        }
        if (offset % 8 != 0 && std::any_of(s_.spec_constants.begin(), s_.spec_constants.end(),
                                           [](const SpecConstant& c) { return spec_size(c.type) == 8; })) {
            lines.add("uint32_t _pad" + std::to_string(pad_index++) + " = 0;", "trailing padding to 8-byte alignment");
            offset += 4;
        }
        spec_size_ = offset;
        out += lines.render("  ");
        if (!lines.empty()) out += "\n";
        out += "  VkSpecializationInfo info() const;\n";
        if (s_.stage == Stage::Compute) out += "  std::array<uint32_t, 3> workgroup_size() const;\n";
        out += "};\n";
        if (spec_size_ != 0) out += "static_assert(sizeof(Spec) == " + std::to_string(spec_size_) + ");\n";
        return out;
    }

    std::string spec_definitions() const {
        std::string out = "\n";
        if (s_.spec_constants.empty()) {
            out += "inline VkSpecializationInfo Spec::info() const { return {0, nullptr, 0, nullptr}; }\n";
        } else {
            out += "inline constexpr VkSpecializationMapEntry kSpecMapEntries[] = {\n";
            for (const SpecConstant& c : s_.spec_constants) {
                out += "    {" + std::to_string(c.constant_id) + ", offsetof(Spec, " + cpp_identifier(c.name) +
                       "), sizeof(" + spec_cpp_type(c.type) + ")},\n";
            }
            out += "};\n\n";
            out +=
                "inline VkSpecializationInfo Spec::info() const {\n"
                "  return {" +
                std::to_string(s_.spec_constants.size()) + ", kSpecMapEntries, sizeof(Spec), this};\n}\n";
        }
        if (s_.stage == Stage::Compute) {
            out += "\ninline std::array<uint32_t, 3> Spec::workgroup_size() const {\n  return {";
            for (int d = 0; d < 3; ++d) {
                if (d) out += ", ";
                const SpecConstant* c = s_.workgroup_size_ids[d] ? spec_by_id(*s_.workgroup_size_ids[d]) : nullptr;
                if (c == nullptr) {
                    // Qualified: a specialization constant may itself be called kWorkgroupSize.
                    out +=
                        "::" + options_.cpp_namespace + "::" + s_.name + "::kWorkgroupSize[" + std::to_string(d) + "]";
                } else if (c->type == SpecConstant::Type::UInt32) {
                    out += cpp_identifier(c->name);
                } else {
                    out += "static_cast<uint32_t>(" + cpp_identifier(c->name) + ")";
                }
            }
            out += "};\n}\n";
        }
        return out;
    }

    std::string bindings() const {
        std::string out = "\n// The resources of one dispatch or draw, one field per binding.\nstruct Bindings {\n";
        CommentedLines lines;
        for (const Binding& b : s_.bindings) {
            lines.add(binding_field_type(b) + " " + cpp_identifier(b.name) + "{};",
                      "binding " + std::to_string(b.binding) + ": " + descriptor_words(b));
        }
        out += lines.render("  ");
        out += "};\n";
        return out;
    }

    // The writes that push a Bindings: shared by the compute dispatch and by host code that
    // records draws with a vertex and a fragment shader (see Module).
    std::string descriptor_writes() const {
        const std::string n = std::to_string(s_.bindings.size());
        std::string out =
            "\n// The descriptor writes for `bindings`, for vkCmdPushDescriptorSetKHR (dstSet is ignored).\n"
            "inline constexpr uint32_t kDescriptorWriteCount = " +
            n + ";\n";
        if (s_.bindings.empty()) {
            return out + "inline void write_descriptors(const Bindings&, VkWriteDescriptorSet*) {}\n";
        }
        out += "inline void write_descriptors(const Bindings& bindings, VkWriteDescriptorSet* writes) {\n";
        size_t i = 0;
        for (const Binding& b : s_.bindings) {
            const std::string field = "bindings." + cpp_identifier(b.name);
            const std::string pointer = b.is_array ? field + ".data()" : "&" + field;
            out += "  writes[" + std::to_string(i++) +
                   "] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, VK_NULL_HANDLE, kBinding" +
                   camel_case(b.name) + ", 0, " + std::to_string(b.count) + ", " + descriptor_type(b.kind) +
                   ",\n               " + (is_buffer(b.kind) ? "nullptr, " + pointer : pointer + ", nullptr") +
                   ", nullptr};\n";
        }
        out += "}\n";
        return out;
    }

    // The shader as one type, so host code can be templated on shaders: a graphics pipeline
    // takes a vertex and a fragment Module and merges their layouts.
    std::string module_type() const {
        const std::string qualified = "::" + options_.cpp_namespace + "::" + s_.name + "::";
        std::string out =
            "\n// This shader as a type, for host code templated on shaders (e.g. a graphics pipeline\n"
            "// made of a vertex and a fragment Module).\n"
            "struct Module {\n";
        out += "  using Spec = " + qualified + "Spec;\n";
        out += "  using Bindings = " + qualified + "Bindings;\n";
        if (s_.push) out += "  using Push = " + qualified + "Push;\n";
        out +=
            "  static constexpr VkShaderStageFlagBits stage = kStage;\n"
            "  static constexpr const char* entry_point = kEntryPoint;\n"
            "  static constexpr const uint32_t* spirv = kSpirv;\n"
            "  static constexpr size_t spirv_bytes = sizeof(kSpirv);\n";
        if (s_.bindings.empty()) {
            out +=
                "  static constexpr const VkDescriptorSetLayoutBinding* set_layout_bindings = nullptr;\n"
                "  static constexpr uint32_t set_layout_binding_count = 0;\n"
                "  static constexpr const Access* binding_access = nullptr;\n"
                "  static constexpr const char* const* binding_names = nullptr;\n";
        } else {
            out +=
                "  static constexpr const VkDescriptorSetLayoutBinding* set_layout_bindings = kSetLayoutBindings;\n"
                "  static constexpr uint32_t set_layout_binding_count = " +
                std::to_string(s_.bindings.size()) +
                ";\n"
                "  static constexpr const Access* binding_access = kBindingAccess;\n"
                "  static constexpr const char* const* binding_names = kBindingNames;\n";
        }
        out += std::string("  static constexpr bool has_push_constants = ") + (s_.push ? "true" : "false") + ";\n";
        out += s_.push ? "  static constexpr VkPushConstantRange push_constant_range = kPushConstantRange;\n"
                       : "  static constexpr VkPushConstantRange push_constant_range = {kStage, 0, 0};\n";
        out +=
            "  static constexpr uint32_t descriptor_write_count = kDescriptorWriteCount;\n"
            "  static void write_descriptors(const Bindings& bindings, VkWriteDescriptorSet* writes) {\n"
            "    " +
            qualified +
            "write_descriptors(bindings, writes);\n"
            "  }\n"
            "};\n";
        return out;
    }

    std::string spirv() const {
        std::string out = "\n// The SPIR-V module (" + std::to_string(s_.words.size()) + " words).\n";
        out += "inline constexpr uint32_t kSpirv[] = {";
        char buf[16];
        for (size_t i = 0; i < s_.words.size(); ++i) {
            if (i % 8 == 0) out += "\n   ";
            std::snprintf(buf, sizeof(buf), " 0x%08x,", s_.words[i]);
            out += buf;
        }
        out += "\n};\n";
        return out;
    }

    const ShaderModel& s_;
    const EmitOptions& options_;
    uint32_t spec_size_ = 0;
};

}  // namespace

std::string emit_shader_header(const ShaderModel& shader, const EmitOptions& options) {
    return ShaderEmitter(shader, options).run();
}

}  // namespace vplkit::codegen
