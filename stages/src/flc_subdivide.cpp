#include "vplkit/error.hpp"
#include "vplkit/shaders/flc_subdivide.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/flc.hpp"

#include "scene_draws.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace vplkit::stages {

uint64_t flc_max_candidates(const Device& device) {
    return std::min(kFlcMaxCandidates, device.limits().max_storage_buffer_range / sizeof(shaders::FlcCandidate));
}

FlcSubdivision flc_subdivision_for(std::span<const double> triangle_areas, const FlcPartition& partition,
                                   uint64_t max_candidates) {
    validate(partition);
    max_candidates = std::min(max_candidates, kFlcMaxCandidates);
    const double target = 0.99 * flc_divergence_area(partition);
    FlcSubdivision out;
    uint64_t total = 0;
    for (size_t t = 0; t < triangle_areas.size(); ++t) {
        const double area = triangle_areas[t];
        if (!std::isfinite(area) || !(area > target)) continue;
        const double root = std::ceil(std::sqrt(area / target));
        // Beyond the candidate limit the count cannot fit anyway (and side^2 could overflow).
        auto side = root < double(max_candidates) ? uint64_t(root) : max_candidates;
        while (side < max_candidates && double(side) * double(side) * target < area) ++side;  // the root's rounding
        if (side >= max_candidates || total + triangle_areas.size() + side * side > max_candidates) {
            throw Error(
                "flc: the divergent triangles' subdivision needs more than " +
                std::to_string(max_candidates - std::min<uint64_t>(max_candidates, triangle_areas.size())) +
                " sub-triangles (triangle " + std::to_string(t) + ", area " + std::to_string(area) + ", needs " +
                std::to_string(side) +
                "^2): the partition needs a larger s0 (fewer VPLs per point), a larger level_count or a larger mu");
        }
        out.entries.push_back({uint32_t(t), uint32_t(side), uint32_t(total)});
        total += side * side;
    }
    out.sub_count = uint32_t(total);
    return out;
}

void add_flc_subdivide_pass(Device& device, StepList& passes, const FlcSubdivideBuffers& buffers,
                            const FlcPartition& partition, const FlcSubdivision& subdivision, uint32_t triangle_count,
                            uint32_t seed) {
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({buffers.vertices, buffers.indices, buffers.vertex_random, buffers.entries, buffers.candidates,
                  buffers.triangle_albedo, buffers.candidate_albedo});
    validate(partition);
    if (triangle_count == 0) throw Error("flc subdivide: the scene has no triangle");
    const uint64_t candidates = uint64_t(triangle_count) + subdivision.sub_count;
    if (candidates > flc_max_candidates(device)) {  // the dispatch folds; the buffers must fit a binding
        throw Error("flc subdivide: " + std::to_string(candidates) + " candidates, at most " +
                    std::to_string(flc_max_candidates(device)) + " on this device (32 bytes each, bound whole)");
    }
    const auto need = [](const BufferView& view, uint64_t bytes, const char* what) {
        if (view.size < bytes) {
            throw Error("flc subdivide: '" + std::string(what) + "' has " + std::to_string(view.size) + " bytes, " +
                        std::to_string(bytes) + " needed");
        }
    };
    const uint64_t entry_bytes = sizeof(shaders::FlcSubdivisionEntry);
    need(buffers.entries, std::max<uint64_t>(subdivision.entries.size(), 1) * entry_bytes, "entries");
    need(buffers.candidates, candidates * sizeof(shaders::FlcCandidate), "candidates");
    need(buffers.triangle_albedo, uint64_t(triangle_count) * 4 * sizeof(float), "triangle albedo");
    need(buffers.candidate_albedo, candidates * 4 * sizeof(float), "candidate albedo");
    const SceneBuffers scene{.vertices = buffers.vertices, .indices = buffers.indices, .addressed = buffers.addressed};
    check_scene_range(scene, device.limits().max_storage_buffer_range, "flc subdivide");
    namespace shader = shaders::flc_subdivide;
    shader::Spec spec{};
    spec.kSceneAddressed = scene.addressed;
    const auto& pipeline = device.pipeline<shader::Pipeline>(spec);
    shader::Bindings bindings;
    shader::Push push{};
    bind_scene(device.device(), scene, push, bindings);
    bindings.vertex_random = buffers.vertex_random.descriptor();
    bindings.entries = buffers.entries.descriptor();
    bindings.candidates = buffers.candidates.descriptor();
    bindings.triangle_albedo = buffers.triangle_albedo.descriptor();
    bindings.candidate_albedo = buffers.candidate_albedo.descriptor();
    push.triangle_count = triangle_count;
    push.entry_count = uint32_t(subdivision.entries.size());
    push.sub_count = subdivision.sub_count;
    push.seed = seed;
    push.level_count = int32_t(partition.level_count);
    push.s0 = partition.s0;
    push.mu = partition.mu;
    const auto threads = uint32_t(candidates);
    add_dispatch<shader::Module>(passes, "flc subdivide", pipeline, bindings, push, threads);
}

}  // namespace vplkit::stages
