#include "vpl_keys_reference.hpp"

#include <algorithm>
#include <cmath>

namespace vplkit::reference {

Box vpl_bounds(std::span<const std::array<float, 3>> positions) {
    Box box;
    box.lo.fill(INFINITY);
    box.hi.fill(-INFINITY);
    for (const auto& p : positions) {
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
            continue;
        }
        box.empty = false;
        for (int axis = 0; axis < 3; ++axis) {
            box.lo[axis] = std::min(box.lo[axis], double(p[axis]));
            box.hi[axis] = std::max(box.hi[axis], double(p[axis]));
        }
    }
    return box;
}

CellCode morton_code(const std::array<float, 3>& position, const Box& box) {
    CellCode result;
    result.margin = INFINITY;
    uint32_t cell[3];
    for (int axis = 0; axis < 3; ++axis) {
        double extent = box.hi[axis] - box.lo[axis];
        double t = extent > 0.0 ? (double(position[axis]) - box.lo[axis]) / extent : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        double scaled = t * 1024.0;
        cell[axis] = std::min(uint32_t(std::floor(scaled)), 1023u);
        if (extent > 0.0 && scaled > 0.0 && scaled < 1024.0) {
            double to_border = std::abs(scaled - std::round(scaled));
            result.margin = std::min(result.margin, to_border);
        }
    }
    // Interleave bit by bit, the plainest way: bit b of x goes to 3b+2, of y to 3b+1, of z to 3b.
    for (int bit = 0; bit < 10; ++bit) {
        result.morton |= ((cell[0] >> bit) & 1u) << (3 * bit + 2);
        result.morton |= ((cell[1] >> bit) & 1u) << (3 * bit + 1);
        result.morton |= ((cell[2] >> bit) & 1u) << (3 * bit);
    }
    return result;
}

NormalCode normal_code(const std::array<float, 3>& normal) {
    NormalCode result;
    result.margin = INFINITY;
    uint32_t octant = (normal[0] < 0.0f ? 4u : 0u) | (normal[1] < 0.0f ? 2u : 0u) | (normal[2] < 0.0f ? 1u : 0u);
    double a[3] = {std::abs(double(normal[0])), std::abs(double(normal[1])), std::abs(double(normal[2]))};
    double l1 = a[0] + a[1] + a[2];
    double bary[3];
    for (int c = 0; c < 3; ++c) {
        bary[c] = l1 > 0.0 ? a[c] / l1 : 1.0 / 3.0;
    }
    // Corner triangles at Px, Py, Pz carry codes 2, 0, 1; the central triangle 3 (the SST paper Fig. 3).
    const uint32_t corner_code[3] = {2u, 0u, 1u};
    uint32_t code = octant;
    for (int level = 0; level < 3; ++level) {
        for (int c = 0; c < 3; ++c) {
            result.margin = std::min(result.margin, std::abs(bary[c] - 0.5));
        }
        int corner = -1;
        for (int c = 0; c < 3 && corner < 0; ++c) {
            if (bary[c] > 0.5) {
                corner = c;
            }
        }
        if (corner >= 0) {
            for (int c = 0; c < 3; ++c) {
                bary[c] = c == corner ? 2.0 * bary[c] - 1.0 : 2.0 * bary[c];
            }
            code = (code << 2) | corner_code[corner];
        } else {
            for (double& b : bary) {
                b = 1.0 - 2.0 * b;
            }
            code = (code << 2) | 3u;
        }
    }
    result.code = code;
    return result;
}

VplKey vpl_key(const std::array<float, 3>& position, const std::array<float, 3>& normal, uint32_t id, const Box& box) {
    CellCode cell = morton_code(position, box);
    NormalCode n = normal_code(normal);
    VplKey key;
    key.key = (uint64_t(cell.morton) << 34) | (uint64_t(n.code) << 25) | uint64_t(id);
    key.morton_margin = cell.margin;
    key.normal_margin = n.margin;
    return key;
}

}  // namespace vplkit::reference
