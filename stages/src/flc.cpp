#include "vplkit/stages/flc.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/flc_candidates.hpp"
#include "vplkit/shaders/flc_compact.hpp"
#include "vplkit/shaders/flc_vpl_light.hpp"
#include "vplkit/stages/binding_uses.hpp"

#include "gi_inputs.hpp"
#include "scene_draws.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace vplkit::stages {

namespace {

bool positive(float v) {
    return std::isfinite(v) && v > 0.0f;
}

}  // namespace

FlcPartition flc_partition_for(float scene_radius, float n_avg, uint32_t level_count, float mu) {
    if (!positive(scene_radius)) {
        throw Error("flc: scene radius " + std::to_string(scene_radius) + " must be finite and positive");
    }
    if (!positive(n_avg)) {
        throw Error("flc: VPLs per point (n_avg) " + std::to_string(n_avg) + " must be finite and positive");
    }
    const double d_near = 0.2 * double(scene_radius);
    FlcPartition partition;
    partition.level_count = level_count;
    partition.mu = mu;
    partition.s0 = float(4.0 * std::numbers::pi * d_near * d_near / double(n_avg));
    partition.d0 = float(d_near);
    validate(partition);
    return partition;
}

void validate(const FlcPartition& p) {
    if (p.level_count < 1 || p.level_count > kFlcMaxLevels) {
        throw Error("flc: level count " + std::to_string(p.level_count) + " is outside 1.." +
                    std::to_string(kFlcMaxLevels));
    }
    if (!positive(p.s0)) throw Error("flc: S_0 " + std::to_string(p.s0) + " must be finite and positive");
    if (!positive(p.d0)) throw Error("flc: D_0 " + std::to_string(p.d0) + " must be finite and positive");
    if (!std::isfinite(p.scene_area) || p.scene_area < 0.0f) {
        throw Error("flc: scene area " + std::to_string(p.scene_area) + " must be finite and not negative");
    }
    if (!std::isfinite(p.mu) || !(p.mu > 1.0f)) {
        throw Error("flc: mu " + std::to_string(p.mu) + " must be finite and above 1 (S_k = S_0 mu^k must grow)");
    }
    const double last = double(p.level_count - 1);
    const double s_last = double(p.s0) * std::pow(double(p.mu), last);
    const double d_last = double(p.d0) * std::pow(double(p.mu), 0.5 * last);
    if (!(s_last < 1e30) || !(d_last < 1e30)) {
        throw Error("flc: S_N = " + std::to_string(s_last) + " or D_N = " + std::to_string(d_last) +
                    " overflows float (fewer levels or a smaller mu)");
    }
}

double flc_divergence_area(const FlcPartition& p) {
    double inverse = 0.0;
    for (uint32_t k = 0; k < p.level_count; ++k) inverse += 1.0 / (double(p.s0) * std::pow(double(p.mu), double(k)));
    return 1.0 / inverse;
}

void add_flc_candidates_pass(Device& device, StepList& passes, const FlcCandidateBuffers& buffers,
                             const FlcPartition& partition, uint32_t triangle_count, uint32_t seed) {
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({buffers.vertices, buffers.indices, buffers.vertex_random, buffers.candidates});
    validate(partition);
    if (triangle_count == 0) throw Error("flc candidates: the scene has no triangle");
    const SceneBuffers scene{.vertices = buffers.vertices, .indices = buffers.indices, .addressed = buffers.addressed};
    check_scene_range(scene, device.limits().max_storage_buffer_range, "flc candidates");
    // One random integer per vertex (scene::Vertex is 72 bytes): a scene built by hand, or by a
    // loader that left scene::Scene::vertex_random empty, must not read past it or a stale buffer.
    const uint64_t vertex_count = buffers.vertices.size / sizeof(shaders::SceneVertex);
    if (buffers.vertex_random.size != vertex_count * sizeof(uint32_t)) {
        throw Error("flc candidates: vertex_random holds " +
                    std::to_string(buffers.vertex_random.size / sizeof(uint32_t)) + " entries for " +
                    std::to_string(vertex_count) +
                    " vertices (one random integer per vertex: scene::Scene::vertex_random)");
    }
    namespace shader = shaders::flc_candidates;
    shader::Spec spec{};
    spec.kSceneAddressed = scene.addressed;
    const auto& pipeline = device.pipeline<shader::Pipeline>(spec);
    shader::Bindings bindings;
    shader::Push push{};
    bind_scene(device.device(), scene, push, bindings);
    bindings.vertex_random = buffers.vertex_random.descriptor();
    bindings.candidates = buffers.candidates.descriptor();
    push.triangle_count = triangle_count;
    push.seed = seed;
    push.level_count = int32_t(partition.level_count);
    push.s0 = partition.s0;
    push.mu = partition.mu;
    add_dispatch<shader::Module>(passes, "flc candidates", pipeline, bindings, push, triangle_count);
}

void add_flc_compact_passes(Device& device, StepList& passes, const FlcCompactBuffers& buffers, uint32_t level_count,
                            uint32_t triangle_count) {
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({buffers.candidates, buffers.counts, buffers.kept_triangles, buffers.divergent_triangles});
    if (level_count < 1 || level_count > kFlcMaxLevels) {
        throw Error("flc compact: level count " + std::to_string(level_count) + " is outside 1.." +
                    std::to_string(kFlcMaxLevels));
    }
    if (triangle_count == 0) throw Error("flc compact: the scene has no triangle");
    if (buffers.counts.size < flc_count_bytes(level_count)) {
        throw Error("flc compact: the counts buffer has " + std::to_string(buffers.counts.size) + " bytes, " +
                    std::to_string(flc_count_bytes(level_count)) + " needed for " + std::to_string(level_count) +
                    " levels");
    }
    const BufferView counts = buffers.counts;
    passes.add("flc counts clear", {Use::transfer_dst(counts)}, [counts, level_count](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, counts.buffer, counts.offset, flc_count_bytes(level_count), 0u);
    });
    namespace shader = shaders::flc_compact;
    const auto& pipeline = device.pipeline<shader::Pipeline>();
    shader::Bindings bindings;
    bindings.candidates = buffers.candidates.descriptor();
    bindings.counts = counts.descriptor();
    bindings.kept_triangles = buffers.kept_triangles.descriptor();
    bindings.divergent_triangles = buffers.divergent_triangles.descriptor();
    // One workgroup per dispatch, 256 chunks of its size at most (lavapipe's loop limit); each
    // dispatch continues the lists where the one before left them.
    const uint32_t span = pipeline.workgroup_size[0] * 256u;
    for (uint32_t first = 0; first < triangle_count; first += std::min(span, triangle_count - first)) {
        shader::Push push{};
        push.first = first;
        push.end = first + std::min(span, triangle_count - first);
        add_dispatch<shader::Module>(passes, "flc compact", pipeline, bindings, push,
                                     pipeline.workgroup_size[0]);  // one workgroup
    }
}

void add_flc_vpl_light_pass(Device& device, StepList& passes, const BvhBuffers& bvh, const LightBuffers& lights,
                            const EmitterBuffers& emitters, const FlcVplLightBuffers& buffers,
                            const FlcPartition& partition, uint32_t triangle_count, const FlcVplLightParams& params) {
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({bvh.nodes, bvh.triangles, bvh.alpha, lights.lights, emitters.triangles, buffers.candidates,
                  buffers.counts, buffers.kept_triangles, buffers.triangle_albedo, buffers.vpls});
    validate(partition);
    if (triangle_count == 0) throw Error("flc vpl light: the scene has no triangle");
    if (params.emitter_samples == 0) throw Error("flc vpl light: emitter samples per VPL must be at least 1");
    const auto need = [&](const BufferView& view, uint64_t stride, const char* what) {
        if (view.size < uint64_t(triangle_count) * stride) {
            throw Error("flc vpl light: '" + std::string(what) + "' has " + std::to_string(view.size) + " bytes, " +
                        std::to_string(uint64_t(triangle_count) * stride) + " needed for " +
                        std::to_string(triangle_count) + " triangles");
        }
    };
    need(buffers.candidates, sizeof(shaders::FlcCandidate), "candidates");
    need(buffers.kept_triangles, sizeof(uint32_t), "kept triangles");
    need(buffers.triangle_albedo, 4 * sizeof(float), "triangle albedo");
    need(buffers.vpls, sizeof(shaders::Vpl), "vpls");
    namespace shader = shaders::flc_vpl_light;
    const auto& pipeline = device.pipeline<shader::Pipeline>(bvh_spec<shader::Spec>(bvh));
    shader::Bindings bindings;
    bind_bvh(bindings, bvh);
    bindings.candidates = buffers.candidates.descriptor();
    bindings.counts = buffers.counts.descriptor();
    bindings.kept_triangles = buffers.kept_triangles.descriptor();
    bindings.triangle_albedo = buffers.triangle_albedo.descriptor();
    bindings.lights = lights.lights.descriptor();
    bindings.emitters = emitters.triangles.descriptor();
    bindings.vpls = buffers.vpls.descriptor();
    shader::Push push{};
    push.triangle_count = triangle_count;
    push.light_count = lights.count;
    push.emitter_count = emitters.count;
    push.emitter_samples = params.emitter_samples;
    push.seed = params.seed;
    push.s0 = partition.s0;
    push.mu = partition.mu;
    push.scene_area = partition.scene_area;
    add_dispatch<shader::Module>(passes, "flc vpl light", pipeline, bindings, push, triangle_count);
}

}  // namespace vplkit::stages
