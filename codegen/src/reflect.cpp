// Reflection of one SPIR-V module into the ShaderModel.
//
// SPIRV-Cross gives us the decorations (Offset, ArrayStride, MatrixStride, Binding, SpecId)
// and the debug names; the SPIR-V is built without optimization so OpName/OpMemberName
// survive. We record layouts exactly as declared and never recompute std140/std430 rules:
// the SPIR-V is the single source of truth.
#include "reflect.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <spirv_cross.hpp>

#include "error.hpp"

namespace vplkit::codegen {

namespace {

using spirv_cross::SPIRType;

class Reflector {
public:
    Reflector(const std::string& name, std::vector<uint32_t> words) : compiler_(make_compiler(name, words)) {
        model_.name = name;
        model_.words = std::move(words);
    }

    ShaderModel run() {
        reflect_entry_point();
        const spirv_cross::ShaderResources res = compiler_.get_shader_resources();
        reject(res.atomic_counters, "atomic counter");
        reject(res.acceleration_structures, "acceleration structure");
        reject(res.shader_record_buffers, "shader record buffer");
        for (const auto& r : res.uniform_buffers) add_buffer(r, DescriptorKind::UniformBuffer);
        for (const auto& r : res.storage_buffers) add_buffer(r, DescriptorKind::StorageBuffer);
        for (const auto& r : res.sampled_images) add_image(r, DescriptorKind::CombinedImageSampler);
        for (const auto& r : res.separate_images) add_image(r, DescriptorKind::SampledImage);
        for (const auto& r : res.separate_samplers) add_image(r, DescriptorKind::Sampler);
        for (const auto& r : res.storage_images) add_image(r, DescriptorKind::StorageImage);
        for (const auto& r : res.subpass_inputs) add_image(r, DescriptorKind::InputAttachment);
        std::sort(model_.bindings.begin(), model_.bindings.end(),
                  [](const Binding& a, const Binding& b) { return a.binding < b.binding; });
        for (size_t i = 1; i < model_.bindings.size(); ++i) {
            if (model_.bindings[i].binding == model_.bindings[i - 1].binding) {
                fail("bindings '" + model_.bindings[i - 1].name + "' and '" + model_.bindings[i].name +
                     "' share binding " + std::to_string(model_.bindings[i].binding) +
                     "; aliased descriptors are not supported (one Bindings field per binding)");
            }
        }
        if (res.push_constant_buffers.size() > 1) fail("more than one push-constant block");
        if (!res.push_constant_buffers.empty()) add_push(res.push_constant_buffers.front());
        reflect_spec_constants();
        if (model_.stage == Stage::Compute) reflect_grid_folding();
        return std::move(model_);
    }

private:
    static spirv_cross::Compiler make_compiler(const std::string& name, const std::vector<uint32_t>& words) {
        try {
            return spirv_cross::Compiler(words);
        } catch (const std::exception& e) {
            throw Error("shader '" + name + "': SPIRV-Cross cannot parse the module: " + e.what());
        }
    }

    [[noreturn]] void fail(const std::string& what) const { throw Error("shader '" + model_.name + "': " + what); }

    void reflect_entry_point() {
        const auto entry_points = compiler_.get_entry_points_and_stages();
        if (entry_points.size() != 1) {
            fail("expected exactly one entry point, found " + std::to_string(entry_points.size()));
        }
        const auto& ep = entry_points.front();
        model_.entry_point = ep.name;
        switch (ep.execution_model) {
            case spv::ExecutionModelVertex:
                model_.stage = Stage::Vertex;
                break;
            case spv::ExecutionModelFragment:
                model_.stage = Stage::Fragment;
                break;
            case spv::ExecutionModelGLCompute:
                model_.stage = Stage::Compute;
                break;
            default:
                fail("unsupported stage (only vertex, fragment and compute shaders are supported)");
        }
        if (model_.stage == Stage::Compute) {
            for (uint32_t i = 0; i < 3; ++i) {
                model_.workgroup_size[i] = compiler_.get_execution_mode_argument(spv::ExecutionModeLocalSize, i);
            }
        }
    }

    void reject(const spirv_cross::SmallVector<spirv_cross::Resource>& list, const char* what) const {
        if (!list.empty()) {
            fail(std::string(what) + " '" + list.front().name + "' is not supported by vplkit-codegen");
        }
    }

    // Set, binding, descriptor count and name shared by every kind of descriptor.
    Binding make_binding(const spirv_cross::Resource& r, DescriptorKind kind, const std::string& name) {
        Binding b;
        b.name = name;
        b.kind = kind;
        b.binding = compiler_.get_decoration(r.id, spv::DecorationBinding);
        const uint32_t set = compiler_.get_decoration(r.id, spv::DecorationDescriptorSet);
        if (set != 0) {
            fail("binding '" + name + "' (binding " + std::to_string(b.binding) + ") is in descriptor set " +
                 std::to_string(set) + "; vplkit shaders use set 0 only (push descriptors)");
        }
        const SPIRType& type = compiler_.get_type(r.type_id);
        b.is_array = !type.array.empty();
        for (size_t i = 0; i < type.array.size(); ++i) {
            if (!type.array_size_literal[i]) {
                fail("binding '" + name +
                     "' is a descriptor array sized by a specialization constant; use a literal size");
            }
            if (type.array[i] == 0) {
                fail("binding '" + name + "' is an unsized descriptor array; use a literal size");
            }
            b.count *= type.array[i];
        }
        return b;
    }

    void add_buffer(const spirv_cross::Resource& r, DescriptorKind kind) {
        const std::string block = compiler_.get_name(r.base_type_id);
        std::string instance = compiler_.get_name(r.id);
        if (instance.empty()) instance = block;  // `buffer Foo { ... };` has no instance name
        Binding b = make_binding(r, kind, instance);
        b.block_type = block;
        if (kind == DescriptorKind::StorageBuffer) {
            // A block's flags are the decorations all its members share (glslang puts readonly /
            // writeonly on each member of the block).
            b.access = access_of(compiler_.get_buffer_block_flags(r.id));
        }
        reflect_struct(r.base_type_id, "block '" + block + "'");
        model_.bindings.push_back(std::move(b));
    }

    void add_image(const spirv_cross::Resource& r, DescriptorKind kind) {
        const SPIRType& type = compiler_.get_type(r.base_type_id);
        if (kind != DescriptorKind::Sampler && type.image.dim == spv::DimBuffer) {
            fail("binding '" + r.name + "' is a texel buffer; texel buffers are not supported (use a storage buffer)");
        }
        Binding b = make_binding(r, kind, r.name);
        if (kind == DescriptorKind::StorageImage) b.access = access_of(compiler_.get_decoration_bitset(r.id));
        model_.bindings.push_back(std::move(b));
    }

    static Access access_of(const spirv_cross::Bitset& decorations) {
        const bool no_write = decorations.get(spv::DecorationNonWritable);
        const bool no_read = decorations.get(spv::DecorationNonReadable);
        return no_write ? Access::Read : no_read ? Access::Write : Access::ReadWrite;
    }

    void add_push(const spirv_cross::Resource& r) {
        const SPIRType& type = compiler_.get_type(r.base_type_id);
        PushBlock push;
        push.struct_name = compiler_.get_name(r.base_type_id);
        reflect_struct(r.base_type_id, "push-constant block");
        uint32_t begin = UINT32_MAX, end = 0;
        for (uint32_t i = 0; i < type.member_types.size(); ++i) {
            const uint32_t offset = compiler_.type_struct_member_offset(type, i);
            begin = std::min(begin, offset);
            end = std::max(end, uint32_t(offset + compiler_.get_declared_struct_member_size(type, i)));
        }
        push.offset = begin;
        push.size = end - begin;
        model_.push = push;
    }

    // Records the struct `type_id` and, recursively, every struct it contains.
    void reflect_struct(uint32_t type_id, const std::string& context) {
        const SPIRType& type = compiler_.get_type(type_id);
        StructLayout layout;
        layout.name = compiler_.get_name(type.self);
        layout.shader = model_.name;
        if (layout.name.empty()) {
            fail(context + " has an unnamed struct type; compile the SPIR-V with debug names (no -g0, no optimizer)");
        }
        for (uint32_t i = 0; i < type.member_types.size(); ++i) {
            Member m;
            m.name = compiler_.get_member_name(type.self, i);
            const std::string where = "struct '" + layout.name + "' member '" + m.name + "'";
            if (m.name.empty()) fail("struct '" + layout.name + "' has an unnamed member " + std::to_string(i));
            if (!compiler_.has_member_decoration(type.self, i, spv::DecorationOffset)) {
                fail(where + " has no Offset decoration");
            }
            m.offset = compiler_.type_struct_member_offset(type, i);
            m.type = reflect_member_type(type, i, where);
            if (m.type.is_runtime_array() && i + 1 != type.member_types.size()) {
                fail(where + " is a runtime array but not the last member");
            }
            layout.members.push_back(std::move(m));
        }
        if (layout.members.empty()) fail("struct '" + layout.name + "' is empty");
        model_.structs.push_back(std::move(layout));
    }

    MemberType reflect_member_type(const SPIRType& parent, uint32_t index, const std::string& where) {
        MemberType mt;
        uint32_t id = parent.member_types[index];
        const SPIRType& outer = compiler_.get_type(id);
        // Array dimensions: SPIRV-Cross lists them innermost first; each OpTypeArray carries its
        // own ArrayStride, and parent_type leads one dimension inwards.
        for (size_t k = outer.array.size(); k-- > 0;) {
            const SPIRType& level = compiler_.get_type(id);
            if (!outer.array_size_literal[k]) {
                const std::string constant = compiler_.get_name(outer.array[k]);
                fail(where + " is an array sized by specialization constant" +
                     (constant.empty() ? std::string() : " '" + constant + "'") +
                     "; a header layout needs a literal size (or a runtime array)");
            }
            if (!compiler_.has_decoration(id, spv::DecorationArrayStride))
                fail(where + " is an array without ArrayStride");
            mt.dims.push_back({outer.array[k], compiler_.get_decoration(id, spv::DecorationArrayStride)});
            if (k + 1 != outer.array.size() && outer.array[k] == 0) fail(where + " has an inner runtime dimension");
            id = level.parent_type;
        }
        const SPIRType& elem = compiler_.get_type(id);
        if (elem.pointer) {
            if (elem.storage != spv::StorageClassPhysicalStorageBuffer) fail(where + " is a pointer");
            mt.kind = MemberType::Kind::Scalar;
            mt.scalar = Scalar::DeviceAddress;
            return mt;
        }
        if (elem.basetype == SPIRType::Struct) {
            mt.kind = MemberType::Kind::Struct;
            mt.struct_name = compiler_.get_name(elem.self);
            reflect_struct(id, where);
            if (!mt.dims.empty()) {
                model_.array_uses.push_back({mt.struct_name, mt.dims.back().stride, model_.name, where});
            }
            return mt;
        }
        mt.scalar = scalar_of(elem, where);
        mt.rows = elem.vecsize;
        mt.columns = elem.columns;
        if (elem.columns > 1) {
            mt.kind = MemberType::Kind::Matrix;
            if (compiler_.has_member_decoration(parent.self, index, spv::DecorationRowMajor)) {
                fail(where +
                     " is a row_major matrix; only column-major matrices are supported (drop row_major, transpose on "
                     "the host)");
            }
            mt.matrix_stride = compiler_.type_struct_member_matrix_stride(parent, index);
        } else {
            mt.kind = elem.vecsize > 1 ? MemberType::Kind::Vector : MemberType::Kind::Scalar;
        }
        return mt;
    }

    Scalar scalar_of(const SPIRType& t, const std::string& where) const {
        switch (t.basetype) {
            case SPIRType::SByte:
                return Scalar::Int8;
            case SPIRType::UByte:
                return Scalar::UInt8;
            case SPIRType::Short:
                return Scalar::Int16;
            case SPIRType::UShort:
                return Scalar::UInt16;
            case SPIRType::Int:
                return Scalar::Int32;
            case SPIRType::UInt:
                return Scalar::UInt32;
            case SPIRType::Int64:
                return Scalar::Int64;
            case SPIRType::UInt64:
                return Scalar::UInt64;
            case SPIRType::Float:
                return Scalar::Float32;
            case SPIRType::Double:
                return Scalar::Float64;
            case SPIRType::Half:
                fail(where + " is a 16-bit float; float16 members are not supported");
            case SPIRType::Boolean:
                fail(where + " is a bool; use uint (0 or 1) in blocks");
            default:
                fail(where + " has a type that cannot be placed in a block");
        }
    }

    void reflect_spec_constants() {
        // Workgroup-size constants: glslang makes an unnamed OpSpecConstant per local_size_*_id
        // (even when a named constant_id constant shares the id).
        spirv_cross::SpecializationConstant wg[3];
        compiler_.get_work_group_size_specialization_constants(wg[0], wg[1], wg[2]);
        static const char* const kWorkgroupNames[3] = {"local_size_x", "local_size_y", "local_size_z"};

        // Several OpSpecConstants may share a constant_id (a named constant and glslang's
        // unnamed copy for local_size_*_id). The Spec gets one member per id: the named one,
        // since its name and default are what the author wrote; the Spec always passes the
        // value, so the workgroup size follows it.
        struct Candidate {
            SpecConstant constant;
            bool auto_named;
        };
        std::map<uint32_t, std::vector<Candidate>> by_id;
        for (const auto& sc : compiler_.get_specialization_constants()) {
            SpecConstant c;
            c.constant_id = sc.constant_id;
            c.name = compiler_.get_name(sc.id);
            const bool auto_named = c.name.empty();
            for (int d = 0; d < 3; ++d) {
                if (wg[d].id == sc.id && c.name.empty()) c.name = kWorkgroupNames[d];
            }
            if (c.name.empty()) c.name = "spec_constant_" + std::to_string(sc.constant_id);
            const spirv_cross::SPIRConstant& value = compiler_.get_constant(sc.id);
            const SPIRType& type = compiler_.get_type(value.constant_type);
            switch (type.basetype) {
                case SPIRType::Boolean:
                    c.type = SpecConstant::Type::Bool;
                    break;
                case SPIRType::Int:
                    c.type = SpecConstant::Type::Int32;
                    break;
                case SPIRType::UInt:
                    c.type = SpecConstant::Type::UInt32;
                    break;
                case SPIRType::Float:
                    c.type = SpecConstant::Type::Float32;
                    break;
                case SPIRType::Int64:
                    c.type = SpecConstant::Type::Int64;
                    break;
                case SPIRType::UInt64:
                    c.type = SpecConstant::Type::UInt64;
                    break;
                case SPIRType::Double:
                    c.type = SpecConstant::Type::Float64;
                    break;
                default:
                    fail("specialization constant '" + c.name + "' has an unsupported type");
            }
            if (c.type == SpecConstant::Type::Bool) {
                c.default_bits = value.scalar() != 0;
            } else {
                c.default_bits = type.width == 64 ? value.scalar_u64() : value.scalar();
            }
            by_id[c.constant_id].push_back({c, auto_named});
        }
        std::map<uint32_t, SpecConstant> resolved;
        for (auto& [id, candidates] : by_id) {
            const Candidate* chosen = &candidates.front();
            for (const Candidate& c : candidates) {
                if (c.constant.type != chosen->constant.type) {
                    fail("specialization constants '" + chosen->constant.name + "' and '" + c.constant.name +
                         "' share constant_id " + std::to_string(id) + " with different types");
                }
                if (!c.auto_named) {
                    if (!chosen->auto_named && chosen->constant.name != c.constant.name) {
                        fail("specialization constants '" + chosen->constant.name + "' and '" + c.constant.name +
                             "' share constant_id " + std::to_string(id));
                    }
                    chosen = &c;
                }
            }
            resolved.emplace(id, chosen->constant);
        }
        for (auto& [id, c] : resolved) model_.spec_constants.push_back(c);

        if (model_.stage == Stage::Compute) {
            for (int d = 0; d < 3; ++d) {
                if (wg[d].id == 0) continue;
                model_.workgroup_size_ids[d] = wg[d].constant_id;
                model_.workgroup_size[d] = uint32_t(resolved.at(wg[d].constant_id).default_bits);
            }
        }
    }

    // A shader folds its grid when it calls dispatch.glsl's linear_workgroup_index() (glslang
    // emits only the functions a shader calls, with their debug names). Such a shader must not
    // also read gl_GlobalInvocationID (row 1 of a folded grid would repeat row 0's ids) and its
    // workgroup must be 1D (the index counts gl_LocalInvocationID.x only).
    void reflect_grid_folding() {
        bool calls_linear_index = false;
        bool reads_global_id = false;
        const std::vector<uint32_t>& w = model_.words;
        for (size_t i = 5; i < w.size();) {
            const uint32_t count = w[i] >> 16;
            const uint32_t opcode = w[i] & 0xffffu;
            if (count == 0 || i + count > w.size()) break;
            if (opcode == spv::OpName && count >= 3) {
                const char* name = reinterpret_cast<const char*>(&w[i + 2]);
                const size_t max_length = (count - 2) * sizeof(uint32_t);
                const std::string text(name, strnlen(name, max_length));
                if (text == "linear_workgroup_index(") calls_linear_index = true;
            } else if (opcode == spv::OpDecorate && count >= 4 && w[i + 2] == spv::DecorationBuiltIn &&
                       w[i + 3] == spv::BuiltInGlobalInvocationId) {
                reads_global_id = true;
            }
            i += count;
        }
        if (!calls_linear_index) return;
        if (reads_global_id) {
            fail(
                "takes its index from vplkit/dispatch.glsl (linear_workgroup_index) but also reads "
                "gl_GlobalInvocationID, which a grid folded into rows does not number linearly; use "
                "linear_thread_index()");
        }
        if (model_.workgroup_size[1] != 1 || model_.workgroup_size[2] != 1 || model_.workgroup_size_ids[1] ||
            model_.workgroup_size_ids[2]) {
            fail(
                "takes its index from vplkit/dispatch.glsl (linear_workgroup_index), which needs a 1D "
                "workgroup (local_size_y and local_size_z 1, not specialized)");
        }
        model_.folds_grid = true;
    }

    spirv_cross::Compiler compiler_;
    ShaderModel model_;
};

}  // namespace

ShaderModel reflect_shader(const std::string& name, std::vector<uint32_t> words) {
    try {
        return Reflector(name, std::move(words)).run();
    } catch (const spirv_cross::CompilerError& e) {
        throw Error("shader '" + name + "': SPIRV-Cross: " + e.what());
    }
}

std::vector<uint32_t> read_spirv_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read '" + path + "'");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() < 20 || bytes.size() % 4 != 0) throw Error("'" + path + "' is not a SPIR-V module (bad size)");
    std::vector<uint32_t> words(bytes.size() / 4);
    std::memcpy(words.data(), bytes.data(), bytes.size());
    if (words[0] != 0x07230203u) throw Error("'" + path + "' is not a SPIR-V module (bad magic number)");
    return words;
}

}  // namespace vplkit::codegen
