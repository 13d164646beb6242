// The helpers of shaders/include/vplkit/light_tree.glsl, which sampling shaders share, run on
// every node of a built tree by a test shader (shaders/light_tree_helpers.comp). Exact: index
// arithmetic, and merge() must reproduce each internal node bit for bit (the build sums in the
// same tree order; a box union and a count sum do not round).

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/light_tree.hpp"
#include "vplkit/light_tree_test/light_tree_helpers.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <bit>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace {

using vplkit::shaders::LightTreeNode;
using vplkit::shaders::Vpl;
namespace helpers = vplkit::light_tree_test::light_tree_helpers;
using Result = vplkit::light_tree_test::LightTreeHelperResult;

bool same(const vplkit::light_tree_test::LightTreeNode& a, const LightTreeNode& b) {
    return a.box_min.x == b.box_min.x && a.box_min.y == b.box_min.y && a.box_min.z == b.box_min.z &&
           a.box_max.x == b.box_max.x && a.box_max.y == b.box_max.y && a.box_max.z == b.box_max.z &&
           a.intensity == b.intensity && a.vpl_count == b.vpl_count;
}

}  // namespace

TEST_CASE("light tree helpers: heap indices and merge reproduce the built tree") {
    vplkit::Context& ctx = vplkit::test::context();
    for (uint32_t count : {1u, 2u, 5u, 100u}) {
        CAPTURE(count);
        const uint32_t leaf_count = vplkit::stages::light_tree_leaf_count(count);
        const uint32_t node_count = vplkit::stages::light_tree_node_count(count);
        std::mt19937 rng(count);
        std::uniform_real_distribution<float> u(-3.0f, 3.0f);
        std::vector<Vpl> leaves(leaf_count);
        for (uint32_t i = 0; i < count; ++i) {
            leaves[i].position = {u(rng), u(rng), u(rng)};
            leaves[i].flux = {std::abs(u(rng)), std::abs(u(rng)), i % 7 == 0 ? 0.0f : std::abs(u(rng))};
        }
        auto leaf_buffer = vplkit::Buffer::create(ctx, leaf_count * sizeof(Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                  vplkit::MemoryUse::device, "leaves");
        auto nodes = vplkit::Buffer::create(ctx, node_count * sizeof(LightTreeNode), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                            vplkit::MemoryUse::device, "light tree");
        auto results = vplkit::Buffer::create(ctx, node_count * sizeof(Result), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                              vplkit::MemoryUse::device, "helper results");
        leaf_buffer.upload(leaves);

        vplkit::PassList passes("light tree helpers test");
        vplkit::stages::add_light_tree_passes(ctx, passes, leaf_buffer, nodes, count);
        const auto& pipeline = ctx.pipeline<helpers::Pipeline>();
        passes.add("helpers", {vplkit::Use::read(nodes), vplkit::Use::write(results)}, [&](VkCommandBuffer cmd) {
            helpers::Bindings bindings;
            bindings.nodes = nodes.descriptor();
            bindings.results = results.descriptor();
            helpers::Push push{};
            push.leaf_count = leaf_count;
            pipeline.dispatch(cmd, bindings, push, node_count);
        });
        passes.run(ctx);
        const auto tree = nodes.download<LightTreeNode>(node_count);
        const auto got = results.download<Result>(node_count);

        const uint32_t depth = uint32_t(std::countr_zero(leaf_count));
        for (uint32_t n = 0; n < node_count; ++n) {
            CAPTURE(n);
            const Result& r = got[n];
            const uint32_t level = uint32_t(std::bit_width(n + 1) - 1);
            CHECK(r.level == level);
            CHECK(r.level_start == (1u << level) - 1);
            CHECK(r.left == 2 * n + 1);
            CHECK(r.right == 2 * n + 2);
            if (n > 0) {
                CHECK((r.parent * 2 + 1 == n || r.parent * 2 + 2 == n));
            }
            CHECK(r.first_grandchild == 2 * (2 * n + 1) + 1);  // the left child's left child
            CHECK(r.bogus == (tree[n].vpl_count == 0 ? 1u : 0u));
            if (level == depth) {
                CHECK(r.leaf == n - (leaf_count - 1));
                CHECK(r.leaf_node == n);
                CHECK(r.bogus == (r.leaf >= count ? 1u : 0u));
                CHECK(r.merged.vpl_count == 0);  // the helper shader's empty node
                CHECK(r.merged.box_min.x == std::numeric_limits<float>::max());
                CHECK(r.merged.box_max.z == -std::numeric_limits<float>::max());
                CHECK(r.merged.intensity == 0.0f);
            } else {
                CHECK(r.leaf == 0xffffffffu);
                CHECK(same(r.merged, tree[n]));
            }
        }
    }
}
