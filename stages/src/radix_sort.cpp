#include "vplkit/stages/radix_sort.hpp"

#include "vplkit/barriers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/dispatch_groups.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/radix_copy.hpp"
#include "vplkit/shaders/radix_histogram.hpp"
#include "vplkit/shaders/radix_scan_chunks.hpp"
#include "vplkit/shaders/radix_scan_reduce.hpp"
#include "vplkit/shaders/radix_scatter.hpp"

#include <algorithm>
#include <string>
#include <utility>

namespace vplkit::stages {

namespace {

// Counts per thread of the prefix-sum shaders (their kItemsPerThread).
constexpr uint32_t kScanItemsPerThread = 4;
// Threads per workgroup of the prefix-sum and copy shaders, whose work has no tile: wide
// workgroups make wide scan chunks, so fewer levels (at most the device's limit, >= 128).
constexpr uint32_t kScanWorkgroupSize = 256;
// The scatter's rank counters are 16 bits: a tile's positions must fit.
constexpr uint32_t kMaxTile = 0xffff;

uint64_t ceil_div(uint64_t a, uint64_t b) {
    return (a + b - 1) / b;
}

uint32_t scan_shared_bytes(uint32_t workgroup_size) {
    // radix.glsl: one value per invocation, one offset per run of 16, the total.
    return 4 * (workgroup_size + uint32_t(ceil_div(workgroup_size, 16)) + 1);
}

void check_options(const Limits& info, const RadixSortOptions& options) {
    if (options.key_bits < 1 || options.key_bits > 64) {
        throw Error("radix sort: key_bits " + std::to_string(options.key_bits) + " is outside 1..64");
    }
    if (options.digit_bits != 4 && options.digit_bits != 8) {
        throw Error("radix sort: digit_bits " + std::to_string(options.digit_bits) + " is neither 4 nor 8");
    }
    const uint32_t size = options.workgroup_size;
    if (size < 1 || size > info.max_workgroup_invocations || size > info.max_workgroup_size[0]) {
        throw Error("radix sort: workgroup size " + std::to_string(size) + " is outside 1.." +
                    std::to_string(std::min(info.max_workgroup_invocations, info.max_workgroup_size[0])) +
                    " (the device's limit)");
    }
    if (uint64_t(size) * options.items_per_thread > kMaxTile) {
        throw Error("radix sort: workgroup size " + std::to_string(size) + " x " +
                    std::to_string(options.items_per_thread) + " items per thread is a tile of more than " +
                    std::to_string(kMaxTile) + " pairs (the rank counters are 16 bits)");
    }
    const uint32_t shared = radix_sort_shared_bytes(options);
    if (shared > info.max_shared_memory_bytes) {
        throw Error("radix sort: workgroup size " + std::to_string(size) + " with " +
                    std::to_string(options.digit_bits) + "-bit digits needs " + std::to_string(shared) +
                    " bytes of shared memory; the device has " + std::to_string(info.max_shared_memory_bytes) +
                    " (lower the workgroup size)");
    }
}

uint32_t scan_workgroup_size(const Limits& limits) {
    return std::min(kScanWorkgroupSize, limits.max_workgroup_invocations);
}

uint32_t tile_count(const RadixSortOptions& options, uint32_t count) {
    return uint32_t(ceil_div(count, uint64_t(options.workgroup_size) * options.items_per_thread));
}

struct ScanLevel {
    VkDeviceSize offset = 0;
    uint32_t length = 0;
};

// Where each level of the digit-count prefix-sum hierarchy lives in the counts buffer for `count`
// pairs: level 0 holds the tile counts, level i + 1 one sum per chunk of level i, the last fits one chunk.
std::vector<ScanLevel> scan_levels(const Limits& limits, const RadixSortOptions& options, uint32_t count) {
    const uint64_t chunk = uint64_t(scan_workgroup_size(limits)) * kScanItemsPerThread;
    // Descriptor offsets must be multiples of this (a power of two, at most 256 by the spec).
    const VkDeviceSize alignment = std::max<VkDeviceSize>(limits.min_storage_buffer_offset_alignment, 4);
    std::vector<ScanLevel> levels;
    uint64_t length = uint64_t(tile_count(options, count)) << options.digit_bits;
    VkDeviceSize offset = 0;
    while (true) {
        levels.push_back({offset, uint32_t(length)});
        if (length <= chunk) {
            return levels;
        }
        offset = ceil_div(offset + length * sizeof(uint32_t), alignment) * alignment;
        length = ceil_div(length, chunk);
    }
}

// The options as the sorter uses them (items per thread resolved), checked against the device.
RadixSortOptions resolved_options(const Limits& limits, uint32_t max_count, const RadixSortOptions& options) {
    RadixSortOptions resolved = options;
    resolved.items_per_thread = radix_sort_items_per_thread(limits, options);
    check_options(limits, resolved);
    if (max_count < 1) {
        throw Error("radix sort: max_count must be at least 1");
    }
    const uint64_t key_bytes = uint64_t(max_count) * sizeof(uint64_t);
    if (key_bytes > limits.max_storage_buffer_range) {
        throw Error("radix sort: " + std::to_string(max_count) + " keys take " + std::to_string(key_bytes) +
                    " bytes, more than the device's storage-buffer range of " +
                    std::to_string(limits.max_storage_buffer_range));
    }
    // The largest dispatches: one workgroup per tile (histogram, scatter), folded into rows past
    // 65,535 workgroups. The scans have a workgroup per 1024 counts, of which a tile has
    // 2^digit_bits, and the copy loops.
    const uint64_t tiles = tile_count(resolved, max_count);
    shaders::radix_histogram::Pipeline tile_grid;  // groups() needs only the workgroup size
    tile_grid.workgroup_size = {resolved.workgroup_size, 1, 1};
    if (tiles * resolved.workgroup_size > UINT32_MAX) {
        throw Error("radix sort: " + std::to_string(max_count) + " pairs need " + std::to_string(tiles) + " tiles of " +
                    std::to_string(resolved.workgroup_size) + " threads, past 2^32 threads");
    }
    check_dispatch_groups(tile_grid, "radix sort", uint32_t(tiles * resolved.workgroup_size));
    if (VkDeviceSize(scan_levels(limits, resolved, max_count).front().length) * sizeof(uint32_t) >
        limits.max_storage_buffer_range) {
        throw Error("radix sort: the digit counts of " + std::to_string(max_count) +
                    " pairs exceed the device's storage-buffer range (raise items per thread)");
    }
    return resolved;
}

}  // namespace

uint32_t radix_sort_shared_bytes(const RadixSortOptions& options) {
    const uint64_t radix = uint64_t(1) << options.digit_bits;
    const uint64_t bytes = (radix / 2 + 1) * options.workgroup_size * 4  // rank counters, two to a uint, padded
                           + uint64_t(options.workgroup_size) * 4        // run offsets
                           + radix * 4                                   // digit bases
                           + scan_shared_bytes(options.workgroup_size);
    return uint32_t(std::min<uint64_t>(bytes, UINT32_MAX));
}

uint32_t radix_sort_items_per_thread(const Limits& limits, const RadixSortOptions& options) {
    if (options.items_per_thread != 0) {
        return options.items_per_thread;
    }
    return limits.cpu ? 128 : 16;
}

uint32_t radix_sort_pass_count(const RadixSortOptions& options) {
    return uint32_t(ceil_div(options.key_bits, options.digit_bits));
}

RadixSortRequirements radix_sort_requirements(const Limits& limits, uint32_t max_count,
                                              const RadixSortOptions& options) {
    const RadixSortOptions resolved = resolved_options(limits, max_count, options);
    const ScanLevel top = scan_levels(limits, resolved, max_count).back();
    return {uint64_t(max_count) * sizeof(uint64_t), uint64_t(max_count) * sizeof(uint32_t),
            top.offset + VkDeviceSize(top.length) * sizeof(uint32_t)};
}

RadixSorter::RadixSorter(Device& device, uint32_t max_count, const RadixSortOptions& options)
    : limits_(device.limits()), max_count_(max_count) {
    const RadixSortRequirements needs = radix_sort_requirements(limits_, max_count, options);
    ScratchBuffer keys = device.create_scratch_buffer(needs.key_bytes, "radix sort scratch keys");
    ScratchBuffer values = device.create_scratch_buffer(needs.value_bytes, "radix sort scratch values");
    ScratchBuffer counts = device.create_scratch_buffer(needs.count_bytes, "radix sort digit counts");
    scratch_ = {keys.view, values.view, counts.view};
    scratch_owners_ = {keys.owner, values.owner, counts.owner};
    init(device, options);
}

RadixSorter::RadixSorter(Device& device, uint32_t max_count, const RadixSortScratch& scratch,
                         const RadixSortOptions& options)
    : limits_(device.limits()), max_count_(max_count), scratch_(scratch) {
    const RadixSortRequirements needs = radix_sort_requirements(limits_, max_count, options);
    auto check_size = [](const BufferView& buffer, VkDeviceSize bytes, const char* what) {
        if (!buffer || buffer.size < bytes) {
            throw Error(std::string("radix sort: scratch ") + what + " '" + buffer.name + "' holds " +
                        std::to_string(buffer.size) + " bytes; it needs " + std::to_string(bytes));
        }
    };
    check_size(scratch.keys, needs.key_bytes, "keys");
    check_size(scratch.values, needs.value_bytes, "values");
    check_size(scratch.counts, needs.count_bytes, "counts");
    init(device, options);
}

void RadixSorter::init(Device& device, const RadixSortOptions& options) {
    options_ = resolved_options(limits_, max_count_, options);
    shaders::radix_histogram::Spec histogram_spec;
    histogram_spec.local_size_x = options.workgroup_size;
    histogram_spec.items_per_thread = options_.items_per_thread;
    histogram_spec.digit_bits = options.digit_bits;
    shaders::radix_scatter::Spec scatter_spec;
    scatter_spec.local_size_x = options.workgroup_size;
    scatter_spec.items_per_thread = options_.items_per_thread;
    scatter_spec.digit_bits = options.digit_bits;
    shaders::radix_scan_reduce::Spec reduce_spec;
    reduce_spec.local_size_x = scan_workgroup_size();
    shaders::radix_scan_chunks::Spec chunks_spec;
    chunks_spec.local_size_x = scan_workgroup_size();
    shaders::radix_copy::Spec copy_spec;
    copy_spec.local_size_x = scan_workgroup_size();
    histogram_ = &device.pipeline<shaders::radix_histogram::Pipeline>(histogram_spec);
    scan_reduce_ = &device.pipeline<shaders::radix_scan_reduce::Pipeline>(reduce_spec);
    scan_chunks_ = &device.pipeline<shaders::radix_scan_chunks::Pipeline>(chunks_spec);
    scatter_ = &device.pipeline<shaders::radix_scatter::Pipeline>(scatter_spec);
    copy_ = &device.pipeline<shaders::radix_copy::Pipeline>(copy_spec);
}

uint32_t RadixSorter::scan_workgroup_size() const {
    return stages::scan_workgroup_size(limits_);
}

uint32_t RadixSorter::dispatch_count(uint32_t count) const {
    if (count <= 1) {
        return 0;
    }
    const uint32_t passes = radix_sort_pass_count(options_);
    const uint32_t reduce_levels = uint32_t(scan_levels(limits_, options_, count).size()) - 1;
    // Per pass: histogram, a reduce and a chunk scan per lower level, the top scan, the scatter.
    return passes * (3 + 2 * reduce_levels) + passes % 2;
}

void RadixSorter::record(VkCommandBuffer cmd, const BufferView& keys, const BufferView& values, uint32_t count) const {
    if (count <= 1) {
        return;  // already sorted
    }
    if (count > max_count_) {
        throw Error("radix sort: " + std::to_string(count) + " pairs, but the sorter was made for at most " +
                    std::to_string(max_count_));
    }
    if (keys.size < uint64_t(count) * sizeof(uint64_t) || values.size < uint64_t(count) * sizeof(uint32_t)) {
        throw Error("radix sort: buffers '" + keys.name + "' / '" + values.name + "' are too small for " +
                    std::to_string(count) + " pairs");
    }
    const uint32_t size = options_.workgroup_size;
    const uint32_t scan_size = scan_workgroup_size();
    const uint32_t tiles = tile_count(options_, count);
    const std::vector<ScanLevel> levels = scan_levels(limits_, options_, count);
    auto level_descriptor = [this](const ScanLevel& level) {
        return scratch_.counts.descriptor(level.offset, VkDeviceSize(level.length) * sizeof(uint32_t));
    };
    // Exactly the first `count` pairs: a descriptor no larger than the data keeps the sort's
    // reads and writes (and what synchronization validation tracks) to the pairs it sorts.
    const VkDescriptorBufferInfo pairs[2][2] = {
        {keys.descriptor(0, uint64_t(count) * sizeof(uint64_t)),
         values.descriptor(0, uint64_t(count) * sizeof(uint32_t))},
        {scratch_.keys.descriptor(0, uint64_t(count) * sizeof(uint64_t)),
         scratch_.values.descriptor(0, uint64_t(count) * sizeof(uint32_t))},
    };

    const uint32_t passes = radix_sort_pass_count(options_);
    for (uint32_t pass = 0; pass < passes; ++pass) {
        const uint32_t shift = pass * options_.digit_bits;
        const uint32_t bits = std::min(options_.digit_bits, options_.key_bits - shift);
        const auto& in = pairs[pass % 2];
        const auto& out = pairs[(pass + 1) % 2];
        if (pass > 0) {
            compute_barrier(cmd);
        }

        shaders::radix_histogram::Bindings histogram_bindings;
        histogram_bindings.keys = in[0];
        histogram_bindings.counts = level_descriptor(levels[0]);
        shaders::radix_histogram::Push histogram_push{};
        histogram_push.count = count;
        histogram_push.shift = shift;
        histogram_push.bits = bits;
        histogram_push.tile_count = tiles;
        histogram_->dispatch(cmd, histogram_bindings, histogram_push, tiles * size);

        for (size_t level = 0; level + 1 < levels.size(); ++level) {
            compute_barrier(cmd);
            shaders::radix_scan_reduce::Bindings reduce_bindings;
            reduce_bindings.counts = level_descriptor(levels[level]);
            reduce_bindings.chunk_sums = level_descriptor(levels[level + 1]);
            shaders::radix_scan_reduce::Push reduce_push{};
            reduce_push.count = levels[level].length;
            scan_reduce_->dispatch(cmd, reduce_bindings, reduce_push, levels[level + 1].length * scan_size);
        }
        for (size_t level = levels.size(); level-- > 0;) {
            compute_barrier(cmd);
            const bool top = level + 1 == levels.size();
            shaders::radix_scan_chunks::Bindings chunks_bindings;
            chunks_bindings.counts = level_descriptor(levels[level]);
            // The top level reads no chunk offsets, but the binding must still hold a valid buffer.
            chunks_bindings.chunk_offsets = level_descriptor(levels[top ? level : level + 1]);
            shaders::radix_scan_chunks::Push chunks_push{};
            chunks_push.count = levels[level].length;
            chunks_push.add_chunk_offsets = top ? 0u : 1u;
            const uint32_t chunks = top ? 1u : levels[level + 1].length;
            scan_chunks_->dispatch(cmd, chunks_bindings, chunks_push, chunks * scan_size);
        }

        compute_barrier(cmd);
        shaders::radix_scatter::Bindings scatter_bindings;
        scatter_bindings.keys = {in[0], out[0]};
        scatter_bindings.values = {in[1], out[1]};
        scatter_bindings.digit_offsets = level_descriptor(levels[0]);
        shaders::radix_scatter::Push scatter_push{};
        scatter_push.count = count;
        scatter_push.shift = shift;
        scatter_push.bits = bits;
        scatter_push.tile_count = tiles;
        scatter_->dispatch(cmd, scatter_bindings, scatter_push, tiles * size);
    }

    if (passes % 2 == 1) {
        compute_barrier(cmd);
        shaders::radix_copy::Bindings copy_bindings;
        copy_bindings.keys = {pairs[1][0], pairs[0][0]};
        copy_bindings.values = {pairs[1][1], pairs[0][1]};
        shaders::radix_copy::Push copy_push{};
        copy_push.count = count;
        const uint64_t max_threads = uint64_t(limits_.max_workgroup_count[0]) * scan_size;
        copy_->dispatch(cmd, copy_bindings, copy_push, uint32_t(std::min<uint64_t>(count, max_threads)));
    }
}

void RadixSorter::add_pass(StepList& passes, const BufferView& keys, const BufferView& values, uint32_t count,
                           std::string name) {
    if (count > max_count_) {  // fail now, not in the middle of recording
        throw Error("radix sort: " + std::to_string(count) + " pairs, but the sorter was made for at most " +
                    std::to_string(max_count_));
    }
    passes.add(std::move(name),
               {Use::read_write(keys), Use::read_write(values), Use::read_write(scratch_.keys),
                Use::read_write(scratch_.values), Use::read_write(scratch_.counts)},
               [this, keys, values, count](VkCommandBuffer cmd) { record(cmd, keys, values, count); });
}

}  // namespace vplkit::stages
