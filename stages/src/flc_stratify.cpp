// Forward light cuts: the stratified decimation (flc_stratify.comp) and the order it walks.

#include "vplkit/error.hpp"
#include "vplkit/shaders/flc_stratify.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/flc.hpp"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace vplkit::stages {

namespace {

// The 10 bits of v spread to every third bit (Karras 2012, "Maximizing Parallelism in the
// Construction of BVHs, Octrees, and k-d Trees").
uint32_t spread_bits(uint32_t v) {
    v = (v * 0x00010001u) & 0xFF0000FFu;
    v = (v * 0x00000101u) & 0x0F00F00Fu;
    v = (v * 0x00000011u) & 0xC30C30C3u;
    v = (v * 0x00000005u) & 0x49249249u;
    return v;
}

}  // namespace

double flc_fitted_level_area(const FlcPartition& partition, uint32_t level) {
    const double nominal = double(partition.s0) * std::pow(double(partition.mu), double(level));
    const double count = std::floor(double(partition.scene_area) / nominal);
    return count >= 1.0 ? double(partition.scene_area) / count : nominal;
}

std::vector<uint32_t> flc_morton_order(std::span<const glm::vec3> points) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    std::vector<uint32_t> codes(points.size(), 0u);
    for (size_t i = 0; i < points.size(); ++i) {
        uint32_t code = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const float extent = hi[axis] - lo[axis];
            const float unit = extent > 0.0f ? (points[i][axis] - lo[axis]) / extent : 0.0f;
            const float clamped = std::isfinite(unit) ? std::clamp(unit, 0.0f, 1.0f) : 0.0f;
            code |= spread_bits(std::min(uint32_t(clamped * 1024.0f), 1023u)) << (2 - axis);
        }
        codes[i] = code;
    }
    std::vector<uint32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return codes[a] < codes[b]; });
    return order;
}

std::vector<uint32_t> flc_candidate_order(std::span<const uint32_t> triangle_order, const FlcSubdivision& subdivision,
                                          uint32_t triangle_count) {
    if (triangle_order.size() != triangle_count) {
        throw Error("flc: the triangle order holds " + std::to_string(triangle_order.size()) + " entries for " +
                    std::to_string(triangle_count) + " triangles");
    }
    // Each subdivided triangle's entry, by triangle.
    std::vector<int64_t> entry_of(triangle_count, -1);
    for (size_t e = 0; e < subdivision.entries.size(); ++e) {
        const uint32_t t = subdivision.entries[e].triangle;
        if (t >= triangle_count) throw Error("flc: a subdivision entry names triangle " + std::to_string(t));
        entry_of[t] = int64_t(e);
    }
    std::vector<uint32_t> order;
    order.reserve(size_t(triangle_count) + subdivision.sub_count);
    for (uint32_t t : triangle_order) {
        if (t >= triangle_count) throw Error("flc: the triangle order names triangle " + std::to_string(t));
        order.push_back(t);
        if (entry_of[t] < 0) continue;
        const auto& entry = subdivision.entries[size_t(entry_of[t])];
        for (uint32_t s = 0; s < entry.side * entry.side; ++s) order.push_back(triangle_count + entry.first + s);
    }
    if (order.size() != size_t(triangle_count) + subdivision.sub_count) {
        throw Error("flc: the triangle order does not name every triangle once");
    }
    return order;
}

void add_flc_stratify_passes(Device& device, StepList& passes, const FlcStratifyBuffers& buffers,
                             const FlcPartition& partition, uint32_t candidate_count, uint32_t seed) {
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({buffers.candidates, buffers.order, buffers.carries});
    validate(partition);
    if (candidate_count == 0) throw Error("flc stratify: the scene has no triangle");
    const auto need = [](const BufferView& view, uint64_t bytes, const char* what) {
        if (view.size < bytes) {
            throw Error("flc stratify: '" + std::string(what) + "' has " + std::to_string(view.size) + " bytes, " +
                        std::to_string(bytes) + " needed");
        }
    };
    need(buffers.candidates, uint64_t(candidate_count) * sizeof(shaders::FlcCandidate), "candidates");
    need(buffers.order, uint64_t(candidate_count) * sizeof(uint32_t), "order");
    need(buffers.carries, uint64_t(partition.level_count) * sizeof(float), "carries");
    namespace shader = shaders::flc_stratify;
    const auto& pipeline = device.pipeline<shader::Pipeline>();
    shader::Bindings bindings;
    bindings.candidates = buffers.candidates.descriptor();
    bindings.order = buffers.order.descriptor();
    bindings.carries = buffers.carries.descriptor();
    // One workgroup per dispatch; per chunk, one scan of log2(256) = 8 steps per level: at most
    // 4096 / levels chunks keep a dispatch's loop iterations far below lavapipe's 65,535.
    const uint32_t chunks = std::clamp(4096u / partition.level_count, 1u, 256u);
    const uint32_t span = pipeline.workgroup_size[0] * chunks;
    for (uint32_t first = 0; first < candidate_count; first += std::min(span, candidate_count - first)) {
        shader::Push push{};
        push.first = first;
        push.end = first + std::min(span, candidate_count - first);
        push.seed = seed;
        push.level_count = int32_t(partition.level_count);
        push.s0 = partition.s0;
        push.mu = partition.mu;
        push.scene_area = partition.scene_area;
        add_dispatch<shader::Module>(passes, "flc stratify", pipeline, bindings, push,
                                     pipeline.workgroup_size[0]);  // one workgroup
    }
}

}  // namespace vplkit::stages
