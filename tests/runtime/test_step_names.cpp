// StepList::entry()/exit() and the recorded barriers name each resource by the caller's view,
// never by a shader binding ("order", "nodes", "counters"): a frame graph matches them back to its
// own buffers by name. A real chain (VPL keys -> radix sort -> gather leaves -> SST, light tree) over buffers
// whose names no shader binding has.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/leaves.hpp"
#include "vplkit/stages/light_tree.hpp"
#include "vplkit/stages/radix_sort.hpp"
#include "vplkit/stages/sst.hpp"
#include "vplkit/stages/vpl_keys.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <set>
#include <string>
#include <vector>

TEST_CASE("step names: entry, exit and barriers report the caller's view names through a real chain") {
    vplkit::Context& ctx = vplkit::test::context();
    constexpr uint32_t count = 37;
    const uint32_t leaves = vplkit::stages::leaf_count(count);
    auto buffer = [&](VkDeviceSize bytes, const char* name) {
        return vplkit::Buffer::create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                      vplkit::MemoryUse::device, name);
    };
    const auto sort_needs = vplkit::stages::radix_sort_requirements(ctx.limits(), count);
    auto vpls = buffer(count * sizeof(vplkit::shaders::Vpl), "my lights");
    auto bounds = buffer(vplkit::stages::kVplBoundsBytes, "my bounds");
    auto keys = buffer(count * sizeof(uint64_t), "my keys");
    auto values = buffer(count * sizeof(uint32_t), "my order");
    auto scratch_keys = buffer(sort_needs.key_bytes, "my scratch keys");
    auto scratch_values = buffer(sort_needs.value_bytes, "my scratch values");
    auto scratch_counts = buffer(sort_needs.count_bytes, "my scratch counts");
    auto leaf_buffer = buffer(leaves * sizeof(vplkit::shaders::Vpl), "my leaves");
    auto nodes = buffer(vplkit::stages::sst_node_count(count) * sizeof(vplkit::shaders::SstNode), "my tree");
    auto counters = buffer(vplkit::stages::sst_counter_count(count) * sizeof(uint32_t), "my counters");
    auto light_nodes =
        buffer(vplkit::stages::light_tree_node_count(count) * sizeof(vplkit::shaders::LightTreeNode), "my light tree");
    const std::set<std::string> caller_names = {
        "my lights",         "my bounds", "my keys", "my order",    "my scratch keys", "my scratch values",
        "my scratch counts", "my leaves", "my tree", "my counters", "my light tree"};
    // Defined VPLs, so the chain can also run (the names are the point, not the values).
    std::vector<vplkit::shaders::Vpl> lights(count);
    for (uint32_t i = 0; i < count; ++i) {
        lights[i].position = {float(i), float(i % 5), float(i % 3)};
        lights[i].normal = {0.0f, 1.0f, 0.0f};
        lights[i].flux = {1.0f, 1.0f, 1.0f};
    }
    vpls.upload(lights);

    vplkit::stages::RadixSorter sorter(ctx, count, {scratch_keys, scratch_values, scratch_counts});
    vplkit::PassList passes("step names");
    vplkit::stages::add_vpl_key_passes(ctx, passes, {vpls, bounds, keys, values}, count);
    sorter.add_pass(passes, keys, values, count);
    vplkit::stages::add_gather_leaves_pass(ctx, passes, vpls, values, leaf_buffer, count);
    vplkit::stages::add_sst_passes(ctx, passes, leaf_buffer, nodes, counters, count);
    vplkit::stages::add_light_tree_passes(ctx, passes, leaf_buffer, light_nodes, count);

    for (const auto& records : {passes.entry(), passes.exit()}) {
        std::set<std::string> seen;
        for (const vplkit::ResourceUse& use : records) {
            CAPTURE(use.name);
            CAPTURE(use.step);
            CHECK(caller_names.count(use.name) == 1);
            CHECK(seen.insert(use.name).second);  // one record per buffer, each under its own name
        }
        CHECK(seen == caller_names);
    }
    passes.run(ctx);
    REQUIRE(!passes.barriers().empty());
    for (const vplkit::BarrierRecord& barrier : passes.barriers()) {
        CAPTURE(barrier.resource);
        CHECK(caller_names.count(barrier.resource) == 1);
    }
}

TEST_CASE("step names: a view without a name is reported under its binding's name") {
    vplkit::Context& ctx = vplkit::test::context();
    constexpr uint32_t count = 4;
    auto buffer = [&](VkDeviceSize bytes, const char* name) {
        return vplkit::Buffer::create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
    };
    auto vpls = buffer(count * sizeof(vplkit::shaders::Vpl), "my lights");
    auto values = buffer(count * sizeof(uint32_t), "unused");
    auto leaf_buffer = buffer(count * sizeof(vplkit::shaders::Vpl), "my leaves");
    vplkit::BufferView unnamed = values;
    unnamed.name.clear();
    vplkit::StepList steps;
    vplkit::stages::add_gather_leaves_pass(ctx, steps, vpls, unnamed, leaf_buffer, count);
    std::set<std::string> names;
    for (const vplkit::ResourceUse& use : steps.entry()) names.insert(use.name);
    CHECK(names == std::set<std::string>{"my lights", "order", "my leaves"});  // gather_leaves.comp's "order"
}
