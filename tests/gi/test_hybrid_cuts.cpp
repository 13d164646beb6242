// The hybrid method's shallow cuts (hybrid_cut.comp) against the double reference
// (tests/reference/hybrid_reference.cpp) on the tree the GPU built, and their invariants: at
// most cut_size nodes, no two overlapping, in first-leaf order, empty slots at the end.

#include "sampling_setup.hpp"

#include "hybrid_reference.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

namespace {

using namespace vplkit::sampling_test;
namespace ref = vplkit::reference;

constexpr uint32_t kEmpty = 0xFFFFFFFFu;

// The leaves [first, last] below a heap node.
std::pair<uint32_t, uint32_t> leaf_range(uint32_t node, uint32_t leaf_count) {
    uint32_t lo = node, hi = node;
    while (lo < leaf_count - 1) {
        lo = 2 * lo + 1;
        hi = 2 * hi + 2;
    }
    return {lo - (leaf_count - 1), hi - (leaf_count - 1)};
}

ref::CutNode cut_node(const Rendered& r, uint32_t count, uint32_t index) {
    const uint32_t L = r.leaf_count;
    ref::CutNode n;
    if (L == 1 || index < L - 1) {
        const auto& s = r.sst[index];
        n.mean = {s.mean.x, s.mean.y, s.mean.z};
        n.intensity = s.intensity;
        n.box_lo = {s.box_lo.x, s.box_lo.y, s.box_lo.z};
        n.box_hi = {s.box_hi.x, s.box_hi.y, s.box_hi.z};
        n.leaf_count = s.leaf_count;
        return n;
    }
    const uint32_t leaf = index - (L - 1);
    if (leaf >= count) return n;  // padding
    const auto& v = r.leaves[leaf];
    n.mean = n.box_lo = n.box_hi = {v.position.x, v.position.y, v.position.z};
    n.intensity = std::max(0.2126 * v.flux.x + 0.7152 * v.flux.y + 0.0722 * v.flux.z, 0.0);
    n.leaf_count = 1;
    return n;
}

// Hybrid on `scene` with 8 x 8 blocks and cuts of `cut_size` nodes.
Rendered render_hybrid_cuts(const Scene& scene, uint32_t cut_size) {
    RunOptions options;
    options.method = Method::hybrid;
    options.samples_per_pixel = cut_size;
    options.block_size = 8;
    return render(scene, options);
}

}  // namespace

TEST_CASE("hybrid cuts: no overlap, first-leaf order, and the double reference's nodes") {
    for (uint32_t cut_size : {1u, 5u, 16u}) {
        const Scene scene = room(24, 16, 300);
        const Rendered r = render_hybrid_cuts(scene, cut_size);
        const uint32_t blocks_x = 3, blocks_y = 2;
        REQUIRE(r.blocks.size() == blocks_x * blocks_y);
        const double min_distance =
            ref::kVplMinDistanceFraction * ref::scene_scale(reference_triangles(scene.triangles));
        uint32_t matched = 0;
        for (uint32_t b = 0; b < blocks_x * blocks_y; ++b) {
            const auto& block = r.blocks[b];
            REQUIRE(block.covered == 1u);
            REQUIRE(block.cut_size >= 1u);
            REQUIRE(block.cut_size <= cut_size);
            std::vector<uint32_t> gpu;
            for (uint32_t i = 0; i < cut_size; ++i) {
                const uint32_t node = r.cuts[b * cut_size + i];
                if (i < block.cut_size) {
                    REQUIRE(node != kEmpty);
                    gpu.push_back(node);
                } else {
                    CHECK(node == kEmpty);
                }
            }
            // Disjoint leaf ranges in increasing order.
            for (size_t i = 1; i < gpu.size(); ++i) {
                CHECK(leaf_range(gpu[i - 1], r.leaf_count).second < leaf_range(gpu[i], r.leaf_count).first);
            }
            // The representative pixel: find it by position and rebuild its shading point.
            const Pixel* rep = nullptr;
            for (const Pixel& p : scene.pixels) {
                if (p.covered &&
                    glm::distance(p.position, glm::vec3(block.position.x, block.position.y, block.position.z)) == 0.0f)
                    rep = &p;
            }
            REQUIRE(rep != nullptr);
            const ref::ShadingPoint x = shading_point(*rep);
            const glm::vec3 wo = glm::normalize(scene.camera - rep->position);
            const auto expected = ref::hybrid_cut(
                x, {wo.x, wo.y, wo.z}, [&](uint32_t i) { return cut_node(r, uint32_t(scene.vpls.size()), i); },
                r.leaf_count, cut_size, min_distance);
            CHECK(gpu == expected);
            matched += gpu == expected;
        }
        MESSAGE("cut size " << cut_size << ": " << matched << " of " << blocks_x * blocks_y
                            << " blocks match the reference");
    }
}

TEST_CASE(
    "hybrid cuts: every block's cut covers every VPL with light, also those its representative sees from behind") {
    // A cut serves every pixel of its block and the pixels that blend with it: a node left out
    // because the representative pixel sees its box only from behind would lose its light for
    // pixels elsewhere that do see it (with spp >= 2, a representative behind the root's box had
    // an empty cut). The room's floor, wall and ceiling pixels see whole walls of VPLs from
    // behind (coplanar boxes have a zero corner cosine), so every cut size meets such nodes.
    for (uint32_t cut_size : {2u, 5u, 16u}) {
        const Scene scene = room(24, 16, 300);
        const Rendered r = render_hybrid_cuts(scene, cut_size);
        const uint32_t count = uint32_t(scene.vpls.size());
        for (uint32_t b = 0; b < r.blocks.size(); ++b) {
            CAPTURE(cut_size);
            CAPTURE(b);
            std::vector<int> covered(count, 0);
            for (uint32_t i = 0; i < r.blocks[b].cut_size; ++i) {
                const auto [first, last] = leaf_range(r.cuts[b * cut_size + i], r.leaf_count);
                for (uint32_t leaf = first; leaf <= last && leaf < count; ++leaf) ++covered[leaf];
            }
            uint32_t missing = 0;
            for (uint32_t leaf = 0; leaf < count; ++leaf) {
                const auto& f = r.leaves[leaf].flux;
                if (f.x + f.y + f.z > 0.0f && covered[leaf] != 1) ++missing;
            }
            CHECK(missing == 0);
        }
    }
}
