// The compute shaders' Pipeline wrapper in <name>.hpp: its declaration (create, destroy,
// dispatch, groups) and its inline definitions. Apart from emit_shader.cpp, which writes the rest
// of the header, because it is the one part only compute shaders have.
#include "emit_pipeline.hpp"

namespace vplkit::codegen {

namespace {

class PipelineEmitter {
public:
    PipelineEmitter(const ShaderModel& shader, const EmitOptions& options) : s_(shader), options_(options) {}
    std::string push_parameter() const { return s_.push ? "const Push& push, " : ""; }

    std::string pipeline_declaration() const {
        std::string out =
            "\n// The compute pipeline, its layout and its push-descriptor set layout.\n"
            "struct Pipeline {\n";
        // The shader's types, reachable from the pipeline type alone: generic host code (the
        // runtime's pipeline cache, keyed by P and P::Spec) needs nothing but P.
        const std::string qualified = "::" + options_.cpp_namespace + "::" + s_.name + "::";
        out += "  using Spec = " + qualified + "Spec;\n";
        out += "  using Bindings = " + qualified + "Bindings;\n";
        if (s_.push) out += "  using Push = " + qualified + "Push;\n";
        out +=
            "\n"
            "  VkDevice device = VK_NULL_HANDLE;\n"
            "  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;\n"
            "  VkPipelineLayout layout = VK_NULL_HANDLE;\n"
            "  VkPipeline pipeline = VK_NULL_HANDLE;\n"
            "  std::array<uint32_t, 3> workgroup_size = {kWorkgroupSize[0], kWorkgroupSize[1], kWorkgroupSize[2]};\n"
            "  PFN_vkCmdPushDescriptorSetKHR push_descriptor_set = nullptr;  // extension command, fetched by "
            "create()\n\n"
            "  // Creates everything with `spec`; on failure returns the error and leaves *out untouched.\n"
            "  static VkResult create(VkDevice device, VkPipelineCache cache, const Spec& spec, Pipeline* out);\n"
            "  void destroy();\n"
            "  // Binds the pipeline, pushes the descriptors";
        out += s_.push ? " and the push constants" : "";
        out +=
            ", and dispatches\n"
            "  // groups(threads_x, threads_y, threads_z).\n";
        out += "  void dispatch(VkCommandBuffer cmd, const Bindings& bindings, " + push_parameter() +
               "uint32_t threads_x,\n                uint32_t threads_y = 1, uint32_t threads_z = 1) const;\n";
        out +=
            "  // The workgroup counts dispatch() records: ceil(threads / workgroup size) in each\n"
            "  // dimension; when kFoldsGrid, a 1D grid of more than kMaxGroupsPerDimension groups as\n"
            "  // rows (x) of at most that many, y rows, with fewer than y groups past the count.\n"
            "  // Throws std::length_error for a grid it cannot record (naming the shader and counts).\n"
            "  std::array<uint32_t, 3> groups(uint32_t threads_x, uint32_t threads_y = 1, uint32_t threads_z = 1) "
            "const;\n};\n";
        return out;
    }

    std::string pipeline_definitions() const {
        const bool has_set = !s_.bindings.empty();
        const std::string n = std::to_string(s_.bindings.size());
        std::string out =
            "\ninline VkResult Pipeline::create(VkDevice device, VkPipelineCache cache, const Spec& spec, Pipeline* "
            "out) {\n"
            "  Pipeline p;\n"
            "  p.device = device;\n"
            "  p.workgroup_size = spec.workgroup_size();\n"
            "  VkResult result = VK_SUCCESS;\n";
        if (has_set) {
            out +=
                "  p.push_descriptor_set = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(\n"
                "      vkGetDeviceProcAddr(device, \"vkCmdPushDescriptorSetKHR\"));\n"
                "  if (p.push_descriptor_set == nullptr) return VK_ERROR_EXTENSION_NOT_PRESENT;\n\n"
                "  const VkDescriptorSetLayoutCreateInfo set_layout_info = {\n"
                "      VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr,\n"
                "      VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR, " +
                n +
                ", kSetLayoutBindings};\n"
                "  result = vkCreateDescriptorSetLayout(device, &set_layout_info, nullptr, &p.set_layout);\n";
        }
        out +=
            "  if (result == VK_SUCCESS) {\n"
            "    const VkPipelineLayoutCreateInfo layout_info = {\n"
            "        VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0,\n";
        out += has_set ? "        1, &p.set_layout,\n" : "        0, nullptr,\n";
        out += s_.push ? "        1, &kPushConstantRange};\n" : "        0, nullptr};\n";
        out +=
            "    result = vkCreatePipelineLayout(device, &layout_info, nullptr, &p.layout);\n"
            "  }\n"
            "  if (result == VK_SUCCESS) {\n"
            "    const VkShaderModuleCreateInfo module_info = {\n"
            "        VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, sizeof(kSpirv), kSpirv};\n"
            "    VkShaderModule module = VK_NULL_HANDLE;\n"
            "    result = vkCreateShaderModule(device, &module_info, nullptr, &module);\n"
            "    if (result == VK_SUCCESS) {\n"
            "      const VkSpecializationInfo spec_info = spec.info();\n"
            "      const VkComputePipelineCreateInfo pipeline_info = {\n"
            "          VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO, nullptr, 0,\n"
            "          {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, kStage, module, kEntryPoint, "
            "&spec_info},\n"
            "          p.layout, VK_NULL_HANDLE, -1};\n"
            "      result = vkCreateComputePipelines(device, cache, 1, &pipeline_info, nullptr, &p.pipeline);\n"
            "      vkDestroyShaderModule(device, module, nullptr);  // the pipeline keeps what it needs\n"
            "    }\n"
            "  }\n"
            "  if (result != VK_SUCCESS) {\n"
            "    p.destroy();\n"
            "    return result;\n"
            "  }\n"
            "  *out = p;\n"
            "  return VK_SUCCESS;\n"
            "}\n\n";
        out +=
            "inline void Pipeline::destroy() {\n"
            "  if (device != VK_NULL_HANDLE) {\n"
            "    vkDestroyPipeline(device, pipeline, nullptr);\n"
            "    vkDestroyPipelineLayout(device, layout, nullptr);\n"
            "    vkDestroyDescriptorSetLayout(device, set_layout, nullptr);\n"
            "  }\n"
            "  *this = Pipeline{};\n"
            "}\n\n";
        out += "inline void Pipeline::dispatch(VkCommandBuffer cmd, const Bindings& " +
               std::string(has_set ? "bindings" : "") + ", " + push_parameter() +
               "uint32_t threads_x,\n"
               "                               uint32_t threads_y, uint32_t threads_z) const {\n"
               "  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);\n";
        if (has_set) {
            out +=
                "  VkWriteDescriptorSet writes[kDescriptorWriteCount];\n"
                "  write_descriptors(bindings, writes);\n"
                "  push_descriptor_set(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, kDescriptorWriteCount, "
                "writes);\n";
        }
        if (s_.push) {
            out +=
                "  vkCmdPushConstants(cmd, layout, kPushConstantRange.stageFlags, kPushConstantRange.offset,\n"
                "                     kPushConstantRange.size,\n"
                "                     reinterpret_cast<const uint8_t*>(&push) + kPushConstantRange.offset);\n";
        }
        out +=
            "  const std::array<uint32_t, 3> grid = groups(threads_x, threads_y, threads_z);\n"
            "  vkCmdDispatch(cmd, grid[0], grid[1], grid[2]);\n"
            "}\n\n";
        out += groups_definition();
        return out;
    }

    // Pipeline::groups(): the folded grid for kFoldsGrid shaders (docs/codegen.md, "Dispatches past
    // 65,535 workgroups"), else the plain one, and a std::length_error naming the shader when the
    // grid exceeds 65,535 groups in a dimension that cannot be folded.
    std::string groups_definition() const {
        std::string out =
            "inline std::array<uint32_t, 3> Pipeline::groups(uint32_t threads_x, uint32_t threads_y,\n"
            "                                                uint32_t threads_z) const {\n"
            "  // Rounded up without overflow, so threads_x = UINT32_MAX works.\n"
            "  auto round_up = [](uint32_t n, uint32_t size) { return n / size + (n % size != 0); };\n"
            "  const std::array<uint32_t, 3> grid = {round_up(threads_x, workgroup_size[0]),\n"
            "                                        round_up(threads_y, workgroup_size[1]),\n"
            "                                        round_up(threads_z, workgroup_size[2])};\n"
            "  if (grid[0] <= kMaxGroupsPerDimension && grid[1] <= kMaxGroupsPerDimension &&\n"
            "      grid[2] <= kMaxGroupsPerDimension) {\n"
            "    return grid;\n"
            "  }\n";
        if (s_.folds_grid) {
            out +=
                "  if (grid[1] == 1 && grid[2] == 1) {\n"
                "    // As few rows as fit, then as short rows as hold every group: fewer than `rows` extra.\n"
                "    const uint32_t rows = round_up(grid[0], kMaxGroupsPerDimension);\n"
                "    const uint32_t columns = round_up(grid[0], rows);\n"
                "    // The shader's uint index must not wrap: every thread of the grid below 2^32.\n"
                "    if (rows <= kMaxGroupsPerDimension &&\n"
                "        uint64_t(rows) * columns * workgroup_size[0] <= (uint64_t(1) << 32)) {\n"
                "      return {columns, rows, 1};\n"
                "    }\n"
                "  }\n";
        }
        out += "  throw std::length_error(\n      \"shader '" + s_.name +
               "': \" + std::to_string(threads_x) + \" x \" + std::to_string(threads_y) + \" x \" +\n"
               "      std::to_string(threads_z) + \" threads need \" + std::to_string(grid[0]) + \" x \" +\n"
               "      std::to_string(grid[1]) + \" x \" + std::to_string(grid[2]) +\n"
               "      \" workgroups, more than 65535 in a dimension";
        out += s_.folds_grid ? ", and only a 1D grid of at most 65535 x 65535 groups (below 2^32 threads) is "
                               "folded into rows\");\n"
                             : ", and the shader does not take its index from vplkit/dispatch.glsl "
                               "(linear_thread_index) to have its grid folded into rows\");\n";
        out += "}\n";
        return out;
    }

private:
    const ShaderModel& s_;
    const EmitOptions& options_;
};

}  // namespace

std::string emit_pipeline_declaration(const ShaderModel& shader, const EmitOptions& options) {
    return PipelineEmitter(shader, options).pipeline_declaration();
}

std::string emit_pipeline_definitions(const ShaderModel& shader, const EmitOptions& options) {
    return PipelineEmitter(shader, options).pipeline_definitions();
}

}  // namespace vplkit::codegen
