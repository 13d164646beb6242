#pragma once
// CPU reference for the VPL sort keys (shaders/keys/*.comp), written plainly in double precision.
// Besides each key it reports how far the computation was from a quantization decision, so a
// test can tell a real mismatch from float-vs-double rounding at a cell or triangle border.

#include <array>
#include <cstdint>
#include <span>

namespace vplkit::reference {

struct Box {
    std::array<double, 3> lo{};
    std::array<double, 3> hi{};
    bool empty = true;  // no finite position seen
};

// Box of all finite positions (positions are xyz triples).
Box vpl_bounds(std::span<const std::array<float, 3>> positions);

struct CellCode {
    uint32_t morton = 0;  // 30-bit Morton code, x in the highest bit of each triple
    double margin = 0.0;  // distance, in cells, from the nearest cell border on any axis
};
CellCode morton_code(const std::array<float, 3>& position, const Box& box);

struct NormalCode {
    uint32_t code = 0;    // 3 octant bits then 3 x 2 subdivision bits
    double margin = 0.0;  // smallest |barycentric - 1/2| met in a decision
};
NormalCode normal_code(const std::array<float, 3>& normal);

struct VplKey {
    uint64_t key = 0;
    double morton_margin = 0.0;
    double normal_margin = 0.0;
};
VplKey vpl_key(const std::array<float, 3>& position, const std::array<float, 3>& normal, uint32_t id, const Box& box);

}  // namespace vplkit::reference
