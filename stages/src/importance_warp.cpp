#include "vplkit/stages/importance_warp.hpp"

#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/importance_mips.hpp"
#include "vplkit/shaders/warp_samples.hpp"

#include <bit>
#include <string>

namespace vplkit::stages {

namespace {

// 4096^2 x 4/3 floats fit a uint32 index and the 128 MiB storage-buffer limit of lavapipe.
constexpr uint32_t kMaxSize = 4096;

void check_size(uint32_t size) {
    if (size == 0 || size > kMaxSize || !std::has_single_bit(size)) {
        throw Error("importance warp: map size " + std::to_string(size) + " is not a power of two in 1.." +
                    std::to_string(kMaxSize));
    }
}

void check_bytes(const BufferView& buffer, uint64_t bytes, const char* what) {
    if (buffer.size < bytes) {
        throw Error(std::string("importance warp: ") + what + " buffer holds " + std::to_string(buffer.size) +
                    " bytes, needs " + std::to_string(bytes));
    }
}

}  // namespace

uint64_t importance_mip_floats(uint32_t size) {
    check_size(size);
    uint64_t floats = 0;
    for (uint64_t s = size; s >= 1; s /= 2) {
        floats += s * s;
    }
    return floats;
}

uint64_t importance_top_offset(uint32_t size) {
    return importance_mip_floats(size) - 1;
}

void add_importance_mips_passes(Device& device, StepList& passes, const BufferView& importance, const BufferView& mips,
                                uint32_t size) {
    const uint64_t floats = importance_mip_floats(size);
    const uint64_t level0_bytes = uint64_t(size) * size * sizeof(float);
    check_bytes(importance, level0_bytes, "importance");
    check_bytes(mips, floats * sizeof(float), "mip");

    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    passes.add("importance copy", {Use::transfer_src(importance), Use::transfer_dst(mips)},
               [importance, mips, level0_bytes](VkCommandBuffer cmd) {
                   VkBufferCopy region{importance.offset, mips.offset, level0_bytes};
                   vkCmdCopyBuffer(cmd, importance.buffer, mips.buffer, 1, &region);
               });

    add_importance_mip_levels_passes(device, passes, mips, size);
}

void add_importance_mip_levels_passes(Device& device, StepList& passes, const BufferView& mips, uint32_t size) {
    check_bytes(mips, importance_mip_floats(size) * sizeof(float), "mip");
    const auto& pipeline = device.pipeline<shaders::importance_mips::Pipeline>();
    uint32_t src_offset = 0;
    for (uint32_t src_size = size; src_size > 1; src_size /= 2) {
        const uint32_t dst_size = src_size / 2;
        const uint32_t dst_offset = src_offset + src_size * src_size;
        shaders::importance_mips::Bindings bindings;
        bindings.mips = mips.descriptor();
        shaders::importance_mips::Push push{};
        push.src_offset = src_offset;
        push.dst_offset = dst_offset;
        push.dst_size = dst_size;
        add_dispatch(passes, "importance mips", {Use::read_write(mips)}, pipeline, bindings, push, dst_size * dst_size);
        src_offset = dst_offset;
    }
}

void add_warp_samples_pass(Device& device, StepList& passes, const BufferView& mips, const BufferView& samples,
                           const BufferView& count, uint32_t size, uint32_t sample_count, uint32_t seed) {
    if (sample_count == 0) {
        throw Error("importance warp: sample_count is 0");
    }
    const uint64_t floats = importance_mip_floats(size);
    check_bytes(mips, floats * sizeof(float), "mip");
    check_bytes(samples, uint64_t(sample_count) * sizeof(shaders::WarpedSample), "sample");
    check_bytes(count, sizeof(shaders::WarpCountBuffer), "count");

    const auto& pipeline = device.pipeline<shaders::warp_samples::Pipeline>();
    const uint32_t levels = uint32_t(std::countr_zero(size));
    const uint32_t top_offset = uint32_t(floats - 1);
    shaders::warp_samples::Bindings bindings;
    bindings.mips = mips.descriptor();
    bindings.samples = samples.descriptor();
    bindings.result = count.descriptor();
    shaders::warp_samples::Push push{};
    push.sample_count = sample_count;
    push.seed = seed;
    push.levels = levels;
    push.top_offset = top_offset;
    add_dispatch(passes, "warp samples", {Use::read(mips), Use::write(samples), Use::write(count)}, pipeline, bindings,
                 push, sample_count);
}

}  // namespace vplkit::stages
