// The generated headers as an API: Spec data and workgroup sizes, Bindings and descriptor
// arrays, names, layout-only headers for graphics stages, output written once per struct,
// deterministic and only when changed.
#include <doctest/doctest.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <type_traits>
#include <vector>

#include "vplkit/fixtures/fullscreen.hpp"
#include "vplkit/fixtures/layout_only.hpp"
#include "vplkit/fixtures/roundtrip.hpp"
#include "vplkit/fixtures/spec_consts.hpp"

namespace fx = vplkit::fixtures;
namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
    return n;
}

// Runs vplkit-codegen on the fixture modules in the given order; returns its exit status.
int run_codegen(const fs::path& out, const std::vector<std::string>& order) {
    std::string command = std::string("\"") + VPLKIT_CODEGEN_EXE + "\" --namespace vplkit::fixtures" +
                          " --header-dir vplkit/fixtures --out \"" + out.string() + "\"";
    for (const std::string& name : order) {
        command += " --shader " + name + " \"" + (fs::path(VPLKIT_FIXTURE_SPV_DIR) / (name + ".spv")).string() + "\"";
    }
    return std::system(command.c_str());
}

}  // namespace

TEST_CASE("Spec: defaults - explicit 64-bit alignment padding - map entries into the Spec") {
    namespace sc = fx::spec_consts;
    const sc::Spec spec;
    CHECK(spec.kEnabled == VK_TRUE);
    CHECK(spec.kSigned == -7);
    CHECK(spec.kUnsigned == 42u);
    CHECK(spec.kWide == 0x100000002ull);
    CHECK(spec.kScale == 0.25f);
    CHECK(spec.kGroupX == 32u);
    CHECK(spec.local_size_z == 1u);  // unnamed local_size_z_id constant
    static_assert(std::is_standard_layout_v<sc::Spec>);
    static_assert(sizeof(sc::Spec) == 40);  // 4 x 4, pad to 16, 8, 3 x 4, pad to 40
    CHECK(offsetof(sc::Spec, kWide) == 16);

    const VkSpecializationInfo info = spec.info();
    CHECK(info.pData == &spec);
    CHECK(info.dataSize == sizeof(sc::Spec));
    REQUIRE(info.mapEntryCount == 7);
    const std::array<std::array<uint32_t, 3>, 7> expected = {{
        {0, offsetof(sc::Spec, kEnabled), 4},
        {1, offsetof(sc::Spec, kSigned), 4},
        {2, offsetof(sc::Spec, kUnsigned), 4},
        {3, 16, 8},
        {4, offsetof(sc::Spec, kScale), 4},
        {5, offsetof(sc::Spec, kGroupX), 4},
        {6, offsetof(sc::Spec, local_size_z), 4},
    }};
    for (uint32_t i = 0; i < 7; ++i) {
        INFO("entry " << i);
        CHECK(info.pMapEntries[i].constantID == expected[i][0]);
        CHECK(info.pMapEntries[i].offset == expected[i][1]);
        CHECK(info.pMapEntries[i].size == expected[i][2]);
    }
}

TEST_CASE("workgroup size: defaults - and specialized through local_size_x_id") {
    namespace sc = fx::spec_consts;
    CHECK(sc::kWorkgroupSize[0] == 32);  // the named constant's default (kGroupX = 32)
    CHECK(sc::kWorkgroupSize[1] == 2);   // a literal local_size_y
    CHECK(sc::kWorkgroupSize[2] == 1);
    sc::Spec spec;
    CHECK(spec.workgroup_size() == std::array<uint32_t, 3>{32, 2, 1});
    spec.kGroupX = 8;
    spec.local_size_z = 4;
    CHECK(spec.workgroup_size() == std::array<uint32_t, 3>{8, 2, 4});

    CHECK(fx::roundtrip::kWorkgroupSize[0] == 64);
    CHECK(fx::roundtrip::Spec{}.workgroup_size()[0] == 64);
}

TEST_CASE("bindings: named constants - instance names - block names for anonymous blocks") {
    namespace rt = fx::roundtrip;
    CHECK(rt::kBindingStd430Traps == 0);
    CHECK(rt::kBindingStd140Traps == 1);
    CHECK(rt::kBindingScalarTraps == 2);
    CHECK(rt::kBindingItemList == 3);
    CHECK(rt::kBindingVec3List == 4);
    CHECK(rt::kBindingEcho == 5);
    static_assert(std::is_same_v<decltype(rt::Bindings::std140_traps), VkDescriptorBufferInfo>);
    CHECK(rt::kSetLayoutBindings[1].descriptorType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);

    // `buffer Counters { ... };` has no instance name: the block name is used.
    CHECK(fx::spec_consts::kBindingCounters == 1);
    static_assert(std::is_same_v<decltype(fx::spec_consts::Bindings::Counters), VkDescriptorBufferInfo>);
}

TEST_CASE("binding access: readonly / writeonly reflected, uniforms and samplers read") {
    using fx::Access;
    namespace rt = fx::roundtrip;
    REQUIRE(std::size(rt::kBindingAccess) == std::size(rt::kSetLayoutBindings));
    CHECK(rt::kBindingAccess[0] == Access::read_write);  // buffer Std430Traps
    CHECK(rt::kBindingAccess[1] == Access::read);        // uniform Std140Traps
    namespace sc = fx::spec_consts;
    REQUIRE(std::size(sc::kBindingAccess) == 3);
    CHECK(sc::kBindingAccess[0] == Access::read_write);
    CHECK(sc::kBindingAccess[2] == Access::write);  // writeonly buffer Written
    CHECK(sc::kSetLayoutBindings[2].binding == sc::kBindingWrittenList);
    namespace lo = fx::layout_only;
    for (Access a : lo::kBindingAccess) CHECK(a == Access::read);  // samplers, a readonly image, a uniform
    CHECK(std::size(fx::fullscreen::kBindingAccess) == 0);
}

TEST_CASE("dispatch takes a Push only when the shader has push constants") {
    namespace rt = fx::roundtrip;
    namespace sc = fx::spec_consts;
    static_assert(std::is_same_v<decltype(&rt::Pipeline::dispatch),
                                 void (rt::Pipeline::*)(VkCommandBuffer, const rt::Bindings&, const rt::Push&, uint32_t,
                                                        uint32_t, uint32_t) const>);
    static_assert(
        std::is_same_v<decltype(&sc::Pipeline::dispatch), void (sc::Pipeline::*)(VkCommandBuffer, const sc::Bindings&,
                                                                                 uint32_t, uint32_t, uint32_t) const>);
    // The shader's types are reachable from the Pipeline type (generic code takes only P).
    static_assert(std::is_same_v<rt::Pipeline::Spec, rt::Spec>);
    static_assert(std::is_same_v<rt::Pipeline::Bindings, rt::Bindings>);
    static_assert(std::is_same_v<rt::Pipeline::Push, rt::Push>);
    static_assert(std::is_trivially_copyable_v<rt::Spec> && std::is_standard_layout_v<rt::Spec>);
    static_assert(std::is_same_v<decltype(&rt::Pipeline::create),
                                 VkResult (*)(VkDevice, VkPipelineCache, const rt::Spec&, rt::Pipeline*)>);
    CHECK(true);
}

TEST_CASE("graphics stages: layout parts only - descriptor arrays - image descriptors") {
    namespace lo = fx::layout_only;
    CHECK(lo::kStage == VK_SHADER_STAGE_FRAGMENT_BIT);
    REQUIRE(std::size(lo::kSetLayoutBindings) == 5);
    CHECK(lo::kSetLayoutBindings[0].binding == lo::kBindingTextures);
    CHECK(lo::kSetLayoutBindings[0].descriptorType == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    CHECK(lo::kSetLayoutBindings[0].descriptorCount == 2);
    CHECK(lo::kSetLayoutBindings[1].descriptorType == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE);
    CHECK(lo::kSetLayoutBindings[2].descriptorType == VK_DESCRIPTOR_TYPE_SAMPLER);
    CHECK(lo::kSetLayoutBindings[3].descriptorType == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    CHECK(lo::kSetLayoutBindings[4].descriptorType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
    CHECK(lo::kSetLayoutBindings[4].stageFlags == VK_SHADER_STAGE_FRAGMENT_BIT);
    static_assert(std::is_same_v<decltype(lo::Bindings::textures), std::array<VkDescriptorImageInfo, 2>>);
    static_assert(std::is_same_v<decltype(lo::Bindings::plain_sampler), VkDescriptorImageInfo>);
    static_assert(std::is_same_v<lo::Push, fx::FragPush>);
    CHECK(lo::kPushConstantRange.size == 16);

    namespace vs = fx::fullscreen;
    CHECK(vs::kStage == VK_SHADER_STAGE_VERTEX_BIT);
    CHECK(std::size(vs::kSetLayoutBindings) == 0);
    CHECK(vs::Spec{}.info().mapEntryCount == 0);
    CHECK(sizeof(vs::kSpirv) % 4 == 0);
    CHECK(vs::kSpirv[0] == 0x07230203u);  // SPIR-V magic
}

TEST_CASE("types.hpp: each shared struct emitted once") {
    const std::string types = read_text(fs::path(VPLKIT_FIXTURE_HEADER_DIR) / "types.hpp");
    REQUIRE(!types.empty());
    CHECK(count(types, "struct TrapItem {") == 1);   // roundtrip (twice) and spec_consts
    CHECK(count(types, "struct TrapInner {") == 1);  // std430, std140 (roundtrip) and std140 (layout_only)
    CHECK(count(types, "struct ItemList {") == 1);   // roundtrip and spec_consts
    CHECK(count(types, "struct vec3 {") == 1);
}

TEST_CASE("codegen output is deterministic and rewritten only when its text changes") {
    const fs::path scratch = fs::path(VPLKIT_TEST_SCRATCH_DIR) / "deterministic";
    fs::remove_all(scratch);
    const fs::path a = scratch / "a", b = scratch / "b";
    REQUIRE(run_codegen(a, {"roundtrip", "spec_consts", "fullscreen", "layout_only"}) == 0);
    // Another shader order gives the same text (structs sorted by dependency, then name).
    REQUIRE(run_codegen(b, {"layout_only", "fullscreen", "spec_consts", "roundtrip"}) == 0);
    const fs::path dir = "vplkit/fixtures";
    for (const char* file : {"types.hpp", "roundtrip.hpp", "spec_consts.hpp", "fullscreen.hpp", "layout_only.hpp"}) {
        INFO(file);
        const std::string text = read_text(a / dir / file);
        CHECK(!text.empty());
        CHECK(text == read_text(b / dir / file));
        // Same as what the build generated for the fixture library.
        CHECK(text == read_text(fs::path(VPLKIT_FIXTURE_HEADER_DIR) / file));
    }

    // A second run with unchanged input leaves every file alone (timestamps included).
    const auto old_time = fs::file_time_type::clock::now() - std::chrono::hours(1);
    for (const auto& e : fs::directory_iterator(a / dir)) fs::last_write_time(e.path(), old_time);
    REQUIRE(run_codegen(a, {"roundtrip", "spec_consts", "fullscreen", "layout_only"}) == 0);
    size_t files = 0;
    for (const auto& e : fs::directory_iterator(a / dir)) {
        INFO(e.path().filename().string());
        CHECK(e.last_write_time() == old_time);
        ++files;
    }
    CHECK(files == 5);  // and no temporary files left behind
}
