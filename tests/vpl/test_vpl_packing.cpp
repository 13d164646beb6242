// The packing of light-path VPLs (stages::add_pack_vpls_passes): vpl_block_counts.comp counts the
// VPLs of each block of 256 paths, vpl_block_offsets.comp turns the counts into each block's first
// slot (one workgroup, 256 blocks per chunk), compact_vpls.comp copies each path's VPLs there.
// Run alone on made-up traces and compared, element by element and in order, with the CPU's
// concatenation of the paths' VPLs (path order, then bounce). Exact: the passes only move data.
// 70,000 paths make 274 blocks, so the offsets pass runs two chunks and carries the first's total
// into the second (a carry lost, or a block or path out of order, fails the comparison); paths
// with 0 VPLs, whole empty blocks and a partial last block are among them.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/vpl_tracing_buffers.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

namespace {

using vplkit::shaders::Vpl;

// A VPL that names its path and bounce, so any misplacement shows.
Vpl marked_vpl(uint32_t path, uint32_t bounce) {
    Vpl v{};
    v.position = {float(path), float(bounce), -1.0f};
    v.normal = {0.0f, 1.0f, 0.0f};
    v.flux = {float(path % 1000), float(bounce), float(path / 1000)};
    return v;
}

bool same(vplkit::shaders::vec3 a, vplkit::shaders::vec3 b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

// Each path's VPL count: 0..max_bounces from a fixed hash, with every path of blocks 3 and 100 at
// 0 (empty blocks).
uint32_t path_count(uint32_t path, uint32_t max_bounces) {
    const uint32_t block = path / vplkit::stages::vpl_tracing_block_size();
    if (block == 3 || block == 100) return 0;
    uint32_t h = path * 2654435761u;
    h ^= h >> 15;
    return h % (max_bounces + 1);
}

}  // namespace

TEST_CASE("vpl packing: vpl_block_counts, vpl_block_offsets and compact_vpls pack each path's VPLs in path order") {
    vplkit::Context& ctx = vplkit::test::context();
    const vplkit::stages::VplTracingOptions options{70000, 3, 1};
    REQUIRE(options.paths / vplkit::stages::vpl_tracing_block_size() > 256);  // two chunks of blocks
    auto output = vplkit::VplTracingOutput::create(ctx, options);

    std::vector<Vpl> path_vpls(output.capacity, marked_vpl(0xffffff, 99));  // unused slots: never copied
    std::vector<uint32_t> counts(options.paths);
    std::vector<Vpl> expected_vpls;
    std::vector<uint32_t> expected_bounces;
    for (uint32_t p = 0; p < options.paths; ++p) {
        counts[p] = path_count(p, options.max_bounces);
        for (uint32_t k = 0; k < counts[p]; ++k) {
            path_vpls[p * options.max_bounces + k] = marked_vpl(p, k + 1);
            expected_vpls.push_back(marked_vpl(p, k + 1));
            expected_bounces.push_back(k + 1);
        }
    }
    output.path_vpls.upload(path_vpls);
    output.path_counts.upload(counts);
    output.count.upload(std::vector<uint32_t>{0xdeadbeefu, 7u});  // count overwritten, cut_short kept

    vplkit::PassList passes("vpl packing test");
    vplkit::stages::add_pack_vpls_passes(ctx, passes, options, output);
    passes.run(ctx);

    const auto count = output.count.download<uint32_t>(2);
    REQUIRE(count[0] == expected_vpls.size());
    CHECK(count[1] == 7u);
    const auto vpls = output.vpls.download<Vpl>(count[0]);
    const auto bounces = output.bounces.download<uint32_t>(count[0]);
    CHECK(bounces == expected_bounces);
    size_t mismatches = 0;
    for (size_t i = 0; i < vpls.size(); ++i) {
        const Vpl& a = vpls[i];
        const Vpl& b = expected_vpls[i];
        if (!same(a.position, b.position) || !same(a.normal, b.normal) || !same(a.flux, b.flux)) ++mismatches;
    }
    CHECK(mismatches == 0);
}

TEST_CASE("vpl packing: no VPL at all gives a count of 0") {
    vplkit::Context& ctx = vplkit::test::context();
    const vplkit::stages::VplTracingOptions options{300, 2, 1};
    auto output = vplkit::VplTracingOutput::create(ctx, options);
    output.path_counts.upload(std::vector<uint32_t>(options.paths, 0u));
    output.count.upload(std::vector<uint32_t>{123u, 0u});
    vplkit::PassList passes("vpl packing test");
    vplkit::stages::add_pack_vpls_passes(ctx, passes, options, output);
    passes.run(ctx);
    CHECK(output.count.download<uint32_t>(1)[0] == 0u);
}
