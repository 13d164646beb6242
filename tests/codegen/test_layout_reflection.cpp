// Generated headers vs an independent reading of the fixture SPIR-V with SPIRV-Cross, done
// here at test time: every struct reached from a block, member by member (name, offset,
// size), and every shader's bindings, push-constant range, specialization constants and
// embedded words.
#include <doctest/doctest.h>

#include <spirv_cross.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "vplkit/fixtures/fullscreen.hpp"
#include "vplkit/fixtures/layout_only.hpp"
#include "vplkit/fixtures/roundtrip.hpp"
#include "vplkit/fixtures/spec_consts.hpp"

namespace fx = vplkit::fixtures;
using spirv_cross::SPIRType;

namespace {

std::vector<uint32_t> read_words(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<uint32_t> words(bytes.size() / 4);
    std::memcpy(words.data(), bytes.data(), words.size() * 4);
    return words;
}

std::map<std::string, std::vector<uint32_t>> fixture_modules() {
    std::map<std::string, std::vector<uint32_t>> modules;
    for (const auto& entry : std::filesystem::directory_iterator(VPLKIT_FIXTURE_SPV_DIR)) {
        if (entry.path().extension() == ".spv") modules[entry.path().stem().string()] = read_words(entry.path());
    }
    return modules;
}

const fx::struct_info* find_struct(const std::string& name) {
    for (uint32_t i = 0; i < fx::kStructCount; ++i) {
        if (name == fx::kStructs[i].name) return &fx::kStructs[i];
    }
    return nullptr;
}

// Compares one struct (and, recursively, the structs it contains) with kStructs.
void check_struct(const spirv_cross::Compiler& c, const SPIRType& type, std::set<std::string>& seen) {
    const std::string name = c.get_name(type.self);
    INFO("struct " << name);
    const fx::struct_info* info = find_struct(name);
    REQUIRE(info != nullptr);
    seen.insert(name);
    REQUIRE(info->member_count == type.member_types.size());
    bool runtime = false;
    for (uint32_t i = 0; i < type.member_types.size(); ++i) {
        const fx::member_info& m = info->members[i];
        const SPIRType& member_type = c.get_type(type.member_types[i]);
        INFO("member " << c.get_member_name(type.self, i));
        CHECK(std::string(m.name) == c.get_member_name(type.self, i));
        CHECK(m.offset == c.type_struct_member_offset(type, i));
        const size_t declared = c.get_declared_struct_member_size(type, i);
        if (member_type.basetype == SPIRType::Struct) {
            const SPIRType& nested = c.get_type(member_type.self);
            check_struct(c, nested, seen);
            const fx::struct_info* nested_info = find_struct(c.get_name(nested.self));
            REQUIRE(nested_info != nullptr);
            if (member_type.array.empty()) {
                // SPIRV-Cross counts a struct member up to its last member's end; the host struct
                // may add trailing padding (to its array stride, or its C++ alignment), never less.
                CHECK(m.size == nested_info->size);
                CHECK(nested_info->size >= declared);
            } else {
                // An array of structs: the host struct's size is the array stride.
                CHECK(nested_info->size == c.type_struct_member_array_stride(type, i));
                CHECK(m.size == declared);
            }
        } else {
            CHECK(m.size == declared);  // 0 for a runtime array on both sides
        }
        runtime = !member_type.array.empty() && member_type.array.back() == 0 && member_type.array_size_literal.back();
    }
    if (runtime) {
        // A block ending in a runtime array: the host struct is the part before the array.
        const uint32_t last = uint32_t(type.member_types.size() - 1);
        CHECK(info->size == (last == 0 ? 0 : c.type_struct_member_offset(type, last)));
    } else {
        const size_t declared = c.get_declared_struct_size(type);
        CHECK(info->size >= declared);
        CHECK(info->size < declared + 8);  // at most rounding to 8-byte alignment or a vec4 slot
    }
}

struct ShaderHeader {
    const VkDescriptorSetLayoutBinding* bindings;
    size_t binding_count;
    const VkPushConstantRange* push;  // nullptr: no push constants
    VkSpecializationInfo spec;
    const uint32_t* words;
    size_t word_count;
    VkShaderStageFlagBits stage;
};

template <typename Bindings>
ShaderHeader header(const Bindings& bindings, const VkPushConstantRange* push, VkSpecializationInfo spec,
                    const uint32_t* words, size_t word_count, VkShaderStageFlagBits stage) {
    return {std::data(bindings), std::size(bindings), push, spec, words, word_count, stage};
}

// Spec objects outlive the VkSpecializationInfo that points into them.
const fx::roundtrip::Spec kRoundtripSpec;
const fx::spec_consts::Spec kSpecConstsSpec;
const fx::fullscreen::Spec kFullscreenSpec;
const fx::layout_only::Spec kLayoutOnlySpec;

std::map<std::string, ShaderHeader> shader_headers() {
    namespace rt = fx::roundtrip;
    namespace sc = fx::spec_consts;
    namespace fs = fx::fullscreen;
    namespace lo = fx::layout_only;
    return {
        {"roundtrip", header(rt::kSetLayoutBindings, &rt::kPushConstantRange, kRoundtripSpec.info(), rt::kSpirv,
                             std::size(rt::kSpirv), rt::kStage)},
        {"spec_consts", header(sc::kSetLayoutBindings, nullptr, kSpecConstsSpec.info(), sc::kSpirv,
                               std::size(sc::kSpirv), sc::kStage)},
        {"fullscreen", header(fs::kSetLayoutBindings, nullptr, kFullscreenSpec.info(), fs::kSpirv,
                              std::size(fs::kSpirv), fs::kStage)},
        {"layout_only", header(lo::kSetLayoutBindings, &lo::kPushConstantRange, kLayoutOnlySpec.info(), lo::kSpirv,
                               std::size(lo::kSpirv), lo::kStage)},
    };
}

}  // namespace

TEST_CASE("generated struct layouts agree with SPIRV-Cross reflection of the fixture SPIR-V") {
    const auto modules = fixture_modules();
    REQUIRE(modules.size() == 4);
    std::set<std::string> seen;
    for (const auto& [name, words] : modules) {
        INFO("shader " << name);
        spirv_cross::Compiler c(words);
        const spirv_cross::ShaderResources res = c.get_shader_resources();
        for (const auto* list : {&res.uniform_buffers, &res.storage_buffers, &res.push_constant_buffers}) {
            for (const auto& r : *list) check_struct(c, c.get_type(r.base_type_id), seen);
        }
    }
    // And types.hpp holds nothing the shaders do not use.
    CHECK(seen.size() == fx::kStructCount);
}

TEST_CASE("generated bindings - push ranges - specialization constants and SPIR-V agree with the modules") {
    const auto modules = fixture_modules();
    const auto headers = shader_headers();
    REQUIRE(modules.size() == headers.size());
    for (const auto& [name, words] : modules) {
        INFO("shader " << name);
        REQUIRE(headers.count(name) == 1);
        const ShaderHeader& h = headers.at(name);
        CHECK(std::vector<uint32_t>(h.words, h.words + h.word_count) == words);

        spirv_cross::Compiler c(words);
        const spirv_cross::ShaderResources res = c.get_shader_resources();
        std::map<uint32_t, std::pair<VkDescriptorType, uint32_t>> expected;  // binding -> type, count
        auto add = [&](const spirv_cross::SmallVector<spirv_cross::Resource>& list, VkDescriptorType type) {
            for (const auto& r : list) {
                CHECK(c.get_decoration(r.id, spv::DecorationDescriptorSet) == 0);
                const SPIRType& t = c.get_type(r.type_id);
                expected[c.get_decoration(r.id, spv::DecorationBinding)] = {type, t.array.empty() ? 1u : t.array[0]};
            }
        };
        add(res.uniform_buffers, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
        add(res.storage_buffers, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
        add(res.sampled_images, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
        add(res.separate_images, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE);
        add(res.separate_samplers, VK_DESCRIPTOR_TYPE_SAMPLER);
        add(res.storage_images, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
        REQUIRE(h.binding_count == expected.size());
        for (size_t i = 0; i < h.binding_count; ++i) {
            const VkDescriptorSetLayoutBinding& b = h.bindings[i];
            INFO("binding " << b.binding);
            REQUIRE(expected.count(b.binding) == 1);
            CHECK(b.descriptorType == expected[b.binding].first);
            CHECK(b.descriptorCount == expected[b.binding].second);
            CHECK(b.stageFlags == VkShaderStageFlags(h.stage));
        }

        if (res.push_constant_buffers.empty()) {
            CHECK(h.push == nullptr);
        } else {
            REQUIRE(h.push != nullptr);
            CHECK(h.push->offset == 0);
            CHECK(h.push->size == c.get_declared_struct_size(c.get_type(res.push_constant_buffers[0].base_type_id)));
        }

        std::map<uint32_t, uint32_t> spec_sizes;  // constant_id -> bytes
        for (const auto& sc : c.get_specialization_constants()) {
            const SPIRType& t = c.get_type(c.get_constant(sc.id).constant_type);
            spec_sizes[sc.constant_id] = t.basetype == SPIRType::Boolean ? 4 : t.width / 8;
        }
        REQUIRE(h.spec.mapEntryCount == spec_sizes.size());
        for (uint32_t i = 0; i < h.spec.mapEntryCount; ++i) {
            const VkSpecializationMapEntry& e = h.spec.pMapEntries[i];
            INFO("constant_id " << e.constantID);
            REQUIRE(spec_sizes.count(e.constantID) == 1);
            CHECK(e.size == spec_sizes[e.constantID]);
            CHECK(e.offset + e.size <= h.spec.dataSize);
            CHECK(e.offset % e.size == 0);
        }
    }
}
