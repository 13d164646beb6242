// binding_uses: a step's uses derived from a generated shader's reflection (kBindingAccess and
// kBindingNames), and StepList::entry()/exit() over them: what a foreign frame graph reads.

#include "vplkit/shaders/build_sst.hpp"
#include "vplkit/shaders/hybrid_gi.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/steps.hpp"

#include <doctest/doctest.h>

#include <cstdint>

namespace {

// Distinct fake handles: binding_uses and StepList::entry() never call Vulkan.
template <class Handle>
Handle fake(uintptr_t n) {
    return reinterpret_cast<Handle>(n * 16);
}

}  // namespace

TEST_CASE("binding uses: one use per binding, with the access and name the SPIR-V declares") {
    namespace sst = vplkit::shaders::build_sst;
    sst::Bindings b;
    b.leaves = {fake<VkBuffer>(1), 0, 64};
    b.nodes = {fake<VkBuffer>(2), 16, 32};
    b.counters = {fake<VkBuffer>(3), 0, VK_WHOLE_SIZE};
    const auto uses = vplkit::stages::binding_uses<sst::Module>(b);
    REQUIRE(uses.size() == 3);
    CHECK(uses[0].buffer.buffer == fake<VkBuffer>(1));
    CHECK(uses[0].buffer.name == "leaves");
    CHECK(uses[0].access == vplkit::Access::read);  // readonly in build_sst.comp
    CHECK(uses[1].buffer.offset == 16);
    CHECK(uses[1].access == vplkit::Access::read_write);
    CHECK(uses[2].buffer.name == "counters");
    CHECK(uses[2].stages == vplkit::Stage::compute);
}

TEST_CASE("binding uses: image bindings are matched to the given images by view, or refused") {
    namespace gi = vplkit::shaders::hybrid_gi;
    gi::Bindings b;
    const vplkit::ImageView position{fake<VkImage>(10), fake<VkImageView>(11), VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4,
                                     "position"};
    const vplkit::ImageView indirect{fake<VkImage>(12), fake<VkImageView>(13), VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4,
                                     "indirect"};
    b.gbuffer_position = position.descriptor();
    b.indirect = indirect.descriptor();
    b.sst_nodes = {fake<VkBuffer>(1), 0, 64};
    const auto uses = vplkit::stages::binding_uses<gi::Module>(b, {position, indirect});
    // Unset bindings (null handles) are skipped: here the two images and one buffer.
    REQUIRE(uses.size() == 3);
    int images = 0;
    for (const auto& use : uses) {
        if (!use.is_image()) continue;
        ++images;
        CHECK(use.layout == VK_IMAGE_LAYOUT_GENERAL);
        if (use.image.image == indirect.image) CHECK(use.access != vplkit::Access::read);
        if (use.image.image == position.image) CHECK(use.access == vplkit::Access::read);
    }
    CHECK(images == 2);
    CHECK_THROWS_WITH_AS(vplkit::stages::binding_uses<gi::Module>(b, {position}), doctest::Contains("indirect"),
                         vplkit::Error);
}

TEST_CASE("step list: entry and exit name each resource's first and last access") {
    const vplkit::BufferView a{fake<VkBuffer>(1), 0, 64, "a"};
    const vplkit::BufferView b{fake<VkBuffer>(2), 0, 64, "b"};
    vplkit::StepList steps;
    steps.add("write a", {vplkit::Use::write(a)}, [](VkCommandBuffer) {});
    steps.add("a to b", {vplkit::Use::read(a), vplkit::Use::write(b)}, [](VkCommandBuffer) {});
    const auto entry = steps.entry();
    const auto exit = steps.exit();
    REQUIRE(entry.size() == 2);
    REQUIRE(exit.size() == 2);
    CHECK(entry[0].name == "a");
    CHECK(entry[0].step == "write a");
    CHECK(entry[0].access == vplkit::Access::write);
    CHECK(exit[0].step == "a to b");
    CHECK(exit[0].access == vplkit::Access::read);
    CHECK(exit[0].stages == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    CHECK(entry[1].name == "b");
    CHECK(exit[1].access_flags == VK_ACCESS_2_SHADER_WRITE_BIT);
}
