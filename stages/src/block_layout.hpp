#pragma once
// One host block holding several arrays (renderer_scene, the VPL sources), each at a 256-byte
// boundary: the largest minStorageBufferOffsetAlignment Vulkan allows, so every part can be bound
// at its own offset on any device.

#include <array>
#include <cstddef>
#include <cstdint>

namespace vplkit::stages {

inline constexpr uint64_t kBlockPartAlignment = 256;

template <size_t N>
struct BlockLayout {
    std::array<uint64_t, N> offset{};
    std::array<uint64_t, N> size{};
    uint64_t total = 0;
};

// The parts of `size` bytes in that order, each starting at the next aligned offset.
template <size_t N>
BlockLayout<N> block_layout(const std::array<uint64_t, N>& size) {
    BlockLayout<N> l;
    l.size = size;
    for (size_t i = 0; i < N; ++i) {
        l.offset[i] = l.total;
        l.total += (size[i] + kBlockPartAlignment - 1) / kBlockPartAlignment * kBlockPartAlignment;
    }
    return l;
}

}  // namespace vplkit::stages
