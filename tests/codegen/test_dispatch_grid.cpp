// Dispatches past 65,535 workgroups (maxComputeWorkGroupCount's minimum, lavapipe's limit): the
// generated Pipeline::groups() folds a 1D grid into rows for a shader that takes its index from
// vplkit/dispatch.glsl (kFoldsGrid), and throws std::length_error naming the shader for one that
// does not. On lavapipe, grid_coverage.comp runs over 2^24 + 100 elements (262,146 workgroups of
// 64): every element must be counted exactly once, and the threads past the count must be
// exactly the folded grid's surplus. Exact integer checks: nothing here is approximate.
#include <doctest/doctest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "vk_test_device.hpp"
#include "vplkit/grid_fixture/grid_coverage.hpp"
#include "vplkit/fixtures/spec_consts.hpp"
#include "vplkit/shaders/gather_leaves.hpp"
#include "vplkit/shaders/morton_keys.hpp"
#include "vplkit/shaders/radix_scatter.hpp"
#include "vplkit/shaders/smc_select.hpp"
#include "vplkit/shaders/tonemap.hpp"

namespace fx = vplkit::fixtures;
namespace gc = vplkit::grid_fixture::grid_coverage;
using vplkit::codegen_test::HostBuffer;
using vplkit::codegen_test::TestDevice;
using Grid = std::array<uint32_t, 3>;

TEST_CASE("dispatch grid: which shaders fold their grid") {
    CHECK(gc::kFoldsGrid);
    CHECK_FALSE(fx::spec_consts::kFoldsGrid);  // reads gl_GlobalInvocationID
    // The kit's 1D passes take their index from dispatch.glsl; image passes and one-thread passes do not.
    CHECK(vplkit::shaders::morton_keys::kFoldsGrid);
    CHECK(vplkit::shaders::gather_leaves::kFoldsGrid);
    CHECK(vplkit::shaders::radix_scatter::kFoldsGrid);  // tiles by linear_workgroup_index()
    CHECK_FALSE(vplkit::shaders::tonemap::kFoldsGrid);
    CHECK_FALSE(vplkit::shaders::smc_select::kFoldsGrid);
}

TEST_CASE("dispatch grid: groups() folds a 1D grid past 65,535 workgroups into rows") {
    gc::Pipeline pipeline;  // groups() needs only workgroup_size: no device
    REQUIRE(pipeline.workgroup_size == Grid{64, 1, 1});
    CHECK(pipeline.groups(0) == Grid{0, 1, 1});
    CHECK(pipeline.groups(65535u * 64u) == Grid{65535, 1, 1});  // the largest unfolded grid
    CHECK(pipeline.groups(65535u * 64u + 1u) == Grid{32768, 2, 1});
    // 2^24 + 100 threads: 262,146 groups in 5 rows of 52,430 (262,150: 4 groups past the count).
    CHECK(pipeline.groups((1u << 24) + 100u) == Grid{52430, 5, 1});
    // 2D and 3D grids are never folded: within 65,535 a dimension they pass, past it they throw.
    CHECK(pipeline.groups(64, 65535) == Grid{1, 65535, 1});
    CHECK_THROWS_AS(pipeline.groups(65536u * 64u, 2), std::length_error);
    CHECK_THROWS_AS(pipeline.groups(64, 65536), std::length_error);

    pipeline.workgroup_size = {1, 1, 1};
    CHECK(pipeline.groups(65535u * 65535u) == Grid{65535, 65535, 1});  // the largest folded grid
    // More than 65,535 rows of 65,535: refused.
    CHECK_THROWS_WITH_AS(pipeline.groups(65535u * 65535u + 1u),
                         doctest::Contains("shader 'grid_coverage': 4294836226 x 1 x 1 threads need 4294836226"),
                         std::length_error);
    pipeline.workgroup_size = {64, 1, 1};
    // UINT32_MAX threads: 2^26 groups in 1,025 rows of 65,473 would number threads past 2^32.
    CHECK_THROWS_AS(pipeline.groups(UINT32_MAX), std::length_error);
}

TEST_CASE("dispatch grid: a shader that does not fold refuses past 65,535 workgroups, naming itself") {
    fx::spec_consts::Pipeline pipeline;  // gl_GlobalInvocationID.x, workgroups of 32 x 2 x 1
    REQUIRE(pipeline.workgroup_size == Grid{32, 2, 1});
    CHECK(pipeline.groups(65535u * 32u) == Grid{65535, 1, 1});
    CHECK_THROWS_WITH_AS(pipeline.groups(65535u * 32u + 1u),
                         "shader 'spec_consts': 2097121 x 1 x 1 threads need 65536 x 1 x 1 workgroups, more than "
                         "65535 in a dimension, and the shader does not take its index from vplkit/dispatch.glsl "
                         "(linear_thread_index) to have its grid folded into rows",
                         std::length_error);
}

namespace {

// Runs grid_coverage.comp over `count` elements; checks every element was counted exactly once
// and the threads past the count are the grid's surplus.
void check_coverage(TestDevice& device, const gc::Pipeline& pipeline, uint32_t count) {
    const Grid grid = pipeline.groups(count);
    const uint64_t grid_threads = uint64_t(grid[0]) * grid[1] * grid[2] * pipeline.workgroup_size[0];
    HostBuffer coverage =
        device.create_buffer(vplkit::grid_fixture::GridCoverage::kSlotsOffset + uint64_t(count) * sizeof(uint32_t));
    std::memset(coverage.mapped, 0, coverage.size);
    gc::Bindings bindings;
    bindings.coverage = coverage.whole();
    gc::Push push{};
    push.count = count;
    device.run([&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, bindings, push, count); });

    const auto* bytes = static_cast<const uint8_t*>(coverage.mapped);
    uint32_t past_count = 0;
    std::memcpy(&past_count, bytes, sizeof(past_count));
    CHECK(past_count == grid_threads - count);
    const auto* slots = reinterpret_cast<const uint32_t*>(bytes + vplkit::grid_fixture::GridCoverage::kSlotsOffset);
    uint32_t wrong = 0, first_wrong = count;
    for (uint32_t i = 0; i < count; ++i) {
        if (slots[i] != 1u && wrong++ == 0) first_wrong = i;
    }
    INFO("first element not counted exactly once: " << first_wrong << " ("
                                                    << slots[first_wrong < count ? first_wrong : 0] << ")");
    for (int k = 0; k < 8; ++k) MESSAGE("slot " << k << " = " << slots[k] << " at " << (void*)&slots[k]);
    CHECK(wrong == 0);
    device.destroy(coverage);
}

}  // namespace

TEST_CASE("dispatch grid: 2^24 + 100 elements on lavapipe, each counted exactly once") {
    TestDevice device;
    gc::Pipeline pipeline;
    REQUIRE(gc::Pipeline::create(device.device(), VK_NULL_HANDLE, gc::Spec{}, &pipeline) == VK_SUCCESS);
    for (uint32_t count : {1000u, 65535u * 64u + 1u, (1u << 24) + 100u}) {
        CAPTURE(count);
        check_coverage(device, pipeline, count);
    }
    CHECK(device.validation_messages().empty());  // a grid past maxComputeWorkGroupCount would show here
    pipeline.destroy();
}
