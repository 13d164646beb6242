#pragma once
// How many elements a pass works on: a number the host knows, or a count the GPU wrote earlier
// in the same submission (a VPL source's counter), which the passes read when they run. With
// the latter a frame goes from producing VPLs to sampling them without reading anything back.
//
//   add_vpl_key_passes(device, passes, buffers, 4096);                        // host count
//   add_vpl_key_passes(device, passes, buffers,
//                      ElementCount::on_gpu(brsm_count, 0, capacity));          // GPU count
//
// A pass given a GPU count is dispatched for `capacity` elements (the buffers are sized for it)
// and its threads past the count do what the stage documents for padding (keys sort last,
// leaves become bogus padding). The count is clamped to the capacity: producers count attempts
// past their room. Shaders read it through shaders/include/vplkit/element_count.glsl.

#include "vplkit/views.hpp"

#include <cstdint>

namespace vplkit::stages {

struct ElementCount {
    uint32_t capacity = 0;  // the host's count, or the most a GPU count can be
    BufferView buffer;      // empty: the host's count; else the buffer holding the GPU's
    uint32_t word = 0;      // the count's uint32 index in `buffer` (from the view's offset)

    // A host count (implicit, so stage functions that took a number take one still).
    ElementCount(uint32_t host_count = 0) : capacity(host_count) {}

    // The count the GPU writes to uint32 `word` of `buffer`, at most `capacity`.
    static ElementCount on_gpu(const BufferView& buffer, uint32_t word, uint32_t capacity) {
        ElementCount count(capacity);
        count.buffer = buffer;
        count.word = word;
        return count;
    }

    bool is_on_gpu() const { return bool(buffer); }
    // The push constant a shader reads (element_count.glsl's kHostElementCount for a host count).
    uint32_t push_word() const { return is_on_gpu() ? word : 0xffffffffu; }
    // The count buffer's descriptor; a host count binds `stand_in` (a buffer the pass reads
    // anyway), which the shader never reads.
    VkDescriptorBufferInfo descriptor(const BufferView& stand_in) const {
        return is_on_gpu() ? buffer.descriptor(0, (uint64_t(word) + 1) * sizeof(uint32_t)) : stand_in.descriptor();
    }
};

}  // namespace vplkit::stages
