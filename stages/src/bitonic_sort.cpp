#include "vplkit/stages/bitonic_sort.hpp"

#include "vplkit/barriers.hpp"
#include "vplkit/error.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/dispatch_groups.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/shaders/bitonic_global_step.hpp"
#include "vplkit/shaders/bitonic_local.hpp"

#include <bit>
#include <string>

namespace vplkit::stages {

namespace {

// The schedule of the all-ascending bitonic network over `padded` (a power of two) elements:
// one local sort of every tile, then for each larger block size the steps whose pairs are a tile
// or more apart, one dispatch each, and one local dispatch for the rest of that stage.
template <class LocalSort, class GlobalStep, class LocalMerge>
void for_each_dispatch(uint32_t padded, uint32_t tile, LocalSort local_sort, GlobalStep global_step,
                       LocalMerge local_merge) {
    local_sort();
    for (uint64_t block = uint64_t(tile) * 2; block <= padded; block *= 2) {
        for (uint64_t distance = block / 2; distance >= tile; distance /= 2) {
            global_step(uint32_t(block), uint32_t(distance), distance == block / 2);
        }
        local_merge(uint32_t(block));
    }
}

void check_options(const Device& device, uint32_t count, const BitonicSortOptions& options) {
    const uint32_t size = options.workgroup_size;
    if (size < 2 || !std::has_single_bit(size)) {
        throw Error("bitonic sort: workgroup size " + std::to_string(size) + " is not a power of two >= 2");
    }
    if (size > device.limits().max_workgroup_invocations) {
        throw Error("bitonic sort: workgroup size " + std::to_string(size) + " exceeds the device's limit of " +
                    std::to_string(device.limits().max_workgroup_invocations));
    }
    // A tile is 2 x size pairs of (uint64, uint32) in shared memory.
    const uint64_t shared_bytes = uint64_t(size) * 2 * (sizeof(uint64_t) + sizeof(uint32_t));
    if (shared_bytes > device.limits().max_shared_memory_bytes) {
        throw Error("bitonic sort: workgroup size " + std::to_string(size) + " needs " + std::to_string(shared_bytes) +
                    " bytes of shared memory; the device has " +
                    std::to_string(device.limits().max_shared_memory_bytes));
    }
    // The widest dispatches: one thread per pair of the padded count (folded into rows past 65,535
    // workgroups).
    const uint64_t padded = std::bit_ceil(uint64_t(count));
    shaders::bitonic_local::Pipeline pair_grid;  // groups() needs only the workgroup size
    pair_grid.workgroup_size = {size, 1, 1};
    check_dispatch_groups(pair_grid, "bitonic sort", uint32_t(padded / 2));
}

}  // namespace

uint32_t bitonic_sort_dispatch_count(uint32_t count, const BitonicSortOptions& options) {
    if (count <= 1) {
        return 0;
    }
    uint32_t dispatches = 0;
    auto one = [&dispatches](auto...) { ++dispatches; };
    for_each_dispatch(std::bit_ceil(count), 2 * options.workgroup_size, one, one, one);
    return dispatches;
}

void record_bitonic_sort(Device& device, VkCommandBuffer cmd, const BufferView& keys, const BufferView& values,
                         uint32_t count, const BitonicSortOptions& options) {
    if (count <= 1) {
        return;  // already sorted
    }
    check_options(device, count, options);
    if (keys.size < uint64_t(count) * sizeof(uint64_t) || values.size < uint64_t(count) * sizeof(uint32_t)) {
        throw Error("bitonic sort: buffers '" + keys.name + "' / '" + values.name + "' are too small for " +
                    std::to_string(count) + " pairs");
    }

    shaders::bitonic_local::Spec local_spec;
    local_spec.local_size_x = options.workgroup_size;
    shaders::bitonic_global_step::Spec global_spec;
    global_spec.local_size_x = options.workgroup_size;
    const auto& local = device.pipeline<shaders::bitonic_local::Pipeline>(local_spec);
    const auto& global = device.pipeline<shaders::bitonic_global_step::Pipeline>(global_spec);

    const uint32_t padded = std::bit_ceil(count);
    const uint32_t tile = 2 * options.workgroup_size;
    // Threads: one per pair of the padded array, or one per pair of a whole tile for the local passes.
    const uint32_t local_threads = ((padded + tile - 1) / tile) * options.workgroup_size;
    const uint32_t pair_threads = padded / 2;

    shaders::bitonic_local::Bindings local_bindings;
    local_bindings.keys = keys.descriptor();
    local_bindings.values = values.descriptor();
    shaders::bitonic_global_step::Bindings global_bindings;
    global_bindings.keys = keys.descriptor();
    global_bindings.values = values.descriptor();

    bool first = true;
    auto barrier_unless_first = [&]() {
        if (!first) {
            compute_barrier(cmd);
        }
        first = false;
    };
    for_each_dispatch(
        padded, tile,
        [&]() {
            barrier_unless_first();
            shaders::bitonic_local::Push push{};
            push.count = count;
            push.merge_block = 0;
            local.dispatch(cmd, local_bindings, push, local_threads);
        },
        [&](uint32_t block, uint32_t distance, bool flip) {
            barrier_unless_first();
            shaders::bitonic_global_step::Push push{};
            push.count = count;
            push.block = block;
            push.distance = distance;
            push.flip = flip ? 1u : 0u;
            global.dispatch(cmd, global_bindings, push, pair_threads);
        },
        [&](uint32_t block) {
            barrier_unless_first();
            shaders::bitonic_local::Push push{};
            push.count = count;
            push.merge_block = block;
            local.dispatch(cmd, local_bindings, push, local_threads);
        });
}

void add_bitonic_sort_pass(Device& device, StepList& passes, const BufferView& keys, const BufferView& values,
                           uint32_t count, const BitonicSortOptions& options) {
    if (count > 1) {
        check_options(device, count, options);  // fail now, not in the middle of recording
    }
    passes.add("sort", {Use::read_write(keys), Use::read_write(values)},
               [&device, keys, values, count, options](VkCommandBuffer cmd) {
                   record_bitonic_sort(device, cmd, keys, values, count, options);
               });
}

}  // namespace vplkit::stages
