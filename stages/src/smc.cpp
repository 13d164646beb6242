#include "vplkit/stages/smc.hpp"

#include "vplkit/error.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/shaders/smc_camera_rays.hpp"
#include "vplkit/shaders/smc_density.hpp"
#include "vplkit/shaders/smc_follow_surfaces.hpp"
#include "vplkit/shaders/smc_gather_candidates.hpp"
#include "vplkit/shaders/smc_radiosity.hpp"
#include "vplkit/shaders/smc_replace.hpp"
#include "vplkit/shaders/smc_invalid_list.hpp"
#include "vplkit/shaders/smc_revalidate.hpp"
#include "vplkit/shaders/smc_revalidate_claims.hpp"
#include "vplkit/shaders/smc_select.hpp"
#include "vplkit/shaders/smc_selection_keys.hpp"
#include "vplkit/shaders/smc_triangle_slots.hpp"
#include "vplkit/shaders/smc_validate.hpp"
#include "vplkit/shaders/smc_vpls.hpp"
#include "gi_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace vplkit::stages {

void validate(const SmcOptions& o) {
    auto fail = [](const std::string& what) { throw Error("smc: " + what); };
    if (o.budget < 1 || o.budget > kSmcMaxBudget) {
        fail("the VPL budget must be 1.." + std::to_string(kSmcMaxBudget) + ", got " + std::to_string(o.budget));
    }
    if (o.max_moves < 1) fail("max_moves (M_max) must be at least 1");
    if (o.resample_ratio < 1) fail("the resampling ratio must be at least 1 (camera rays per candidate)");
    if (o.radiosity_samples < 1 || o.radiosity_samples > 4096) {
        fail("radiosity samples must be 1..4096, got " + std::to_string(o.radiosity_samples));
    }
    if (o.bounces < 1 || o.bounces > 64) fail("bounces must be 1..64, got " + std::to_string(o.bounces));
    if (o.visibility_tries > 1024) fail("visibility tries must be 0..1024");
    if (o.visibility_rounds > 16) fail("visibility rounds must be 0..16");
    if (!(o.strong_quantile >= 0.0f && o.strong_quantile <= 1.0f)) fail("the strong quantile must be in [0, 1]");
    if (o.surface_samples > kSmcMaxSurfaceSamples) {
        fail("surface samples must be 0.." + std::to_string(kSmcMaxSurfaceSamples) + ", got " +
             std::to_string(o.surface_samples));
    }
    (void)smc_pool_size(o);
}

uint32_t smc_render_neighbours(uint32_t budget) {
    const uint32_t k = uint32_t(std::floor(std::sqrt(double(budget) / 32.0)));
    return std::min(std::max(k, 1u), kSmcMaxNeighbours);
}

uint32_t smc_pool_size(const SmcOptions& o) {
    const uint64_t pool = uint64_t(o.budget) * o.resample_ratio;
    if (pool > (uint64_t(1) << 31)) {
        throw Error("smc: budget x resampling ratio = " + std::to_string(pool) + " camera rays is more than 2^31");
    }
    return uint32_t(pool);
}

SmcRequirements smc_requirements(const SmcOptions& o) {
    SmcRequirements r;
    r.pool = smc_pool_size(o);
    r.state_bytes = uint64_t(o.budget) * sizeof(shaders::SmcVpl);
    r.word_bytes = uint64_t(o.budget) * sizeof(uint32_t);
    r.key_bytes = uint64_t(o.budget) * sizeof(uint64_t);
    r.density_bytes = uint64_t(o.budget) * 4 * sizeof(float);
    r.move_bytes = uint64_t(o.budget) * 2 * sizeof(uint32_t);
    r.hit_bytes = uint64_t(r.pool) * sizeof(shaders::SmcVpl);
    r.pool_key_bytes = uint64_t(r.pool) * sizeof(uint64_t);
    r.pool_value_bytes = uint64_t(r.pool) * sizeof(uint32_t);
    r.counter_bytes = sizeof(shaders::SmcCounters);
    r.vpl_bytes = uint64_t(o.budget) * sizeof(shaders::Vpl);
    return r;
}

namespace {

void check_size(const BufferView& view, uint64_t bytes, const char* what) {
    if (!view || view.size < bytes) {
        throw Error(std::string("smc: the ") + what + " buffer holds fewer than " + std::to_string(bytes) + " bytes");
    }
}

void check_buffers(const SmcBuffers& b, const SmcRequirements& r) {
    check_size(b.state, r.state_bytes, "state");
    check_size(b.candidates, r.state_bytes, "candidates");
    check_size(b.valid, r.word_bytes, "valid");
    check_size(b.invalid_list, r.word_bytes, "invalid list");
    check_size(b.vpl_values, r.word_bytes, "vpl values");
    check_size(b.candidate_values, r.word_bytes, "candidate values");
    check_size(b.vpl_keys, r.key_bytes, "vpl keys");
    check_size(b.candidate_keys, r.key_bytes, "candidate keys");
    check_size(b.candidate_density, r.density_bytes, "candidate density");
    check_size(b.vpl_density, r.density_bytes, "vpl density");
    check_size(b.moves, r.move_bytes, "moves");
    check_size(b.hits, r.hit_bytes, "hits");
    check_size(b.pool_keys, r.pool_key_bytes, "pool keys");
    check_size(b.pool_values, r.pool_value_bytes, "pool values");
    check_size(b.counters, r.counter_bytes, "counters");
    check_size(b.vpls, r.vpl_bytes, "vpls");
}

// The fallback area of a lone VPL: a disc of the scene's size.
float lone_vpl_area(float scene_scale) {
    return 3.14159265f * scene_scale * scene_scale;
}

// Floor of r_k^2: coincident VPLs get the density of points 1e-4 of the scene apart.
float min_neighbour_distance2(float scene_scale) {
    const float d = 1e-4f * scene_scale;
    return d * d;
}

// The pipeline of an SMC shader, specialised for the BVH when it traces rays.
template <class Pipeline>
const Pipeline& smc_pipeline(Device& device, const BvhBuffers& bvh) {
    if constexpr (requires(typename Pipeline::Spec spec) { spec.kBvhAlphaTest; }) {
        return device.pipeline<Pipeline>(bvh_spec<typename Pipeline::Spec>(bvh));
    } else {
        return device.pipeline<Pipeline>();
    }
}

// The bindings an SMC shader shares with the others, by name: the BVH, the scene's sources and
// the buffers of SmcBuffers. The caller binds the rest (bindings named otherwise than the buffer).
template <class Bindings>
Bindings smc_bindings(const SmcScene& scene, const SmcBuffers& buffers) {
    Bindings b;
    if constexpr (requires { b.bvh_nodes; }) bind_bvh(b, scene.bvh);
    if constexpr (requires { b.lights; }) b.lights = scene.sources.lights.descriptor();
    if constexpr (requires { b.emissive; }) b.emissive = scene.sources.emissive.descriptor();
    if constexpr (requires { b.emitter_cdf; }) b.emitter_cdf = scene.sources.emitter_cdf.descriptor();
    if constexpr (requires { b.albedo; }) b.albedo = scene.sources.triangle_albedo.descriptor();
    if constexpr (requires { b.state; }) b.state = buffers.state.descriptor();
    if constexpr (requires { b.valid; }) b.valid = buffers.valid.descriptor();
    if constexpr (requires { b.invalid_list; }) b.invalid_list = buffers.invalid_list.descriptor();
    if constexpr (requires { b.hits; }) b.hits = buffers.hits.descriptor();
    if constexpr (requires { b.candidates; }) b.candidates = buffers.candidates.descriptor();
    if constexpr (requires { b.candidate_density; }) b.candidate_density = buffers.candidate_density.descriptor();
    if constexpr (requires { b.vpl_keys; }) b.vpl_keys = buffers.vpl_keys.descriptor();
    if constexpr (requires { b.vpl_values; }) b.vpl_values = buffers.vpl_values.descriptor();
    if constexpr (requires { b.candidate_keys; }) b.candidate_keys = buffers.candidate_keys.descriptor();
    if constexpr (requires { b.candidate_values; }) b.candidate_values = buffers.candidate_values.descriptor();
    if constexpr (requires { b.moves; }) b.moves = buffers.moves.descriptor();
    if constexpr (requires { b.counters; }) b.counters = buffers.counters.descriptor();
    if constexpr (requires { b.vpls; }) b.vpls = buffers.vpls.descriptor();
    return b;
}

// One step of a shader whose only push constant is the VPL budget.
template <class Module, class Pipeline>
void add_budget_dispatch(StepList& passes, std::string name, const Pipeline& pipeline,
                         const typename Module::Bindings& bindings, uint32_t budget, DispatchThreads threads) {
    typename Pipeline::Push push{};
    push.budget = budget;
    add_dispatch<Module>(passes, std::move(name), pipeline, bindings, push, threads);
}

}  // namespace

void add_smc_density_pass(Device& device, StepList& passes, const BvhBuffers& bvh, const BufferView& state,
                          const BufferView& queries, const BufferView& density, const BufferView& counters,
                          uint32_t budget, uint32_t k, bool queries_are_vpls, uint32_t surface_samples) {
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({bvh.nodes, bvh.triangles, bvh.alpha, state, queries, density, counters});
    if (k < 1 || k > kSmcMaxNeighbours) {
        throw Error("smc density: k must be 1.." + std::to_string(kSmcMaxNeighbours) + ", got " + std::to_string(k));
    }
    if (surface_samples > kSmcMaxSurfaceSamples) {
        throw Error("smc density: surface samples must be 0.." + std::to_string(kSmcMaxSurfaceSamples));
    }
    const auto& pipeline = device.pipeline<shaders::smc_density::Pipeline>(bvh_spec<shaders::smc_density::Spec>(bvh));
    shaders::smc_density::Bindings b;
    bind_bvh(b, bvh);
    b.state = state.descriptor();
    b.queries = queries.descriptor();
    b.density = density.descriptor();
    b.counters = counters.descriptor();
    shaders::smc_density::Push push{};
    push.budget = budget;
    push.k = k;
    push.queries_are_vpls = queries_are_vpls ? 1u : 0u;
    push.min_distance2 = min_neighbour_distance2(bvh.scene_scale);
    push.fallback_area = lone_vpl_area(bvh.scene_scale);
    push.surface_samples = queries_are_vpls ? surface_samples : 0u;
    add_dispatch<shaders::smc_density::Module>(passes, queries_are_vpls ? "smc vpl density" : "smc candidate density",
                                               pipeline, b, push, push.budget);
}

void add_smc_update_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const CameraView& view,
                           const SmcScene& scene, KeyValueSorter& sorter, const SmcBuffers& buffers,
                           const SmcOptions& options, uint32_t iteration, const SmcSceneChange& change) {
    validate(options);
    const SmcRequirements needed = smc_requirements(options);
    check_buffers(buffers, needed);
    if (sorter.max_count() < needed.pool || sorter.options().key_bits < 32) {
        throw Error("smc: the sorter must sort " + std::to_string(needed.pool) + " pairs by 32 or more key bits");
    }
    const BvhBuffers& bvh = scene.bvh;
    const VplSourceBuffers& sources = scene.sources;
    const uint32_t budget = options.budget;
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({bvh.nodes,
                  bvh.triangles,
                  bvh.alpha,
                  sources.lights,
                  sources.emissive,
                  sources.emitter_cdf,
                  sources.triangle_albedo,
                  buffers.candidate_density,
                  buffers.candidate_keys,
                  buffers.candidate_values,
                  buffers.candidates,
                  buffers.counters,
                  buffers.hits,
                  buffers.invalid_list,
                  buffers.moves,
                  buffers.pool_keys,
                  buffers.pool_values,
                  buffers.state,
                  buffers.valid,
                  buffers.vpl_density,
                  buffers.vpl_keys,
                  buffers.vpl_values,
                  buffers.vpls});
    const uint32_t pool = needed.pool;

    // Line 7 over the candidates, line 18 over the VPLs that entered Y or, after the scene moved, all of Y.
    enum class RadiosityOf : uint32_t { candidates = 0, moved_vpls = 1, every_vpl = 2 };  // the shader's modes
    auto add_radiosity_pass = [&](const BufferView& records, RadiosityOf of) {
        const auto& pipeline = smc_pipeline<shaders::smc_radiosity::Pipeline>(device, bvh);
        auto b = smc_bindings<shaders::smc_radiosity::Bindings>(scene, buffers);
        b.records = records.descriptor();
        shaders::smc_radiosity::Push push{};
        push.budget = budget;
        push.samples = options.radiosity_samples;
        push.sample_limit = options.radiosity_samples + 1;
        push.bounces = options.bounces;
        push.step_limit = options.bounces + 1;
        push.punctual_count = sources.punctual_count;
        push.emitter_count = sources.emitter_count;
        push.triangle_count = sources.triangle_count;
        push.mode = uint32_t(of);
        const char* name = of == RadiosityOf::candidates   ? "smc radiosity"
                           : of == RadiosityOf::moved_vpls ? "smc radiosity of new vpls"
                                                           : "smc radiosity of every vpl";
        add_dispatch<shaders::smc_radiosity::Module>(passes, name, pipeline, b, push, push.budget);
    };

    // Everything but |Y| (the first word) starts each update at zero.
    const BufferView counters = buffers.counters;
    passes.add("smc counters clear", {Use::transfer_dst(counters)}, [counters](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, counters.buffer, counters.offset + sizeof(uint32_t),
                        sizeof(shaders::SmcCounters) - sizeof(uint32_t), 0u);
    });

    {
        const auto& pipeline = smc_pipeline<shaders::smc_camera_rays::Pipeline>(device, bvh);
        auto b = smc_bindings<shaders::smc_camera_rays::Bindings>(scene, buffers);
        b.gbuffer_position = gbuffer.position.descriptor();
        b.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
        b.keys = buffers.pool_keys.descriptor();
        b.values = buffers.pool_values.descriptor();
        shaders::smc_camera_rays::Push push{};
        push.ray_count = pool;
        push.seed = options.seed;
        push.iteration = iteration;
        push.triangle_count = sources.triangle_count;
        add_dispatch<shaders::smc_camera_rays::Module>(passes, "smc camera rays", pipeline, b, push, push.ray_count,
                                                       {gbuffer.position, gbuffer.geometric_normal});
    }
    if (change.geometry) {
        // The VPLs move with their triangles: each triangle's BVH slot, then each VPL placed on it.
        const uint32_t slot_count = std::max(sources.triangle_count, 1u);
        check_size(buffers.triangle_slots, uint64_t(slot_count) * sizeof(uint32_t), "triangle slots");
        {
            const auto& pipeline = smc_pipeline<shaders::smc_triangle_slots::Pipeline>(device, bvh);
            shaders::smc_triangle_slots::Bindings b;
            bind_bvh(b, bvh);
            b.slots = buffers.triangle_slots.descriptor();
            shaders::smc_triangle_slots::Push push{};
            push.triangle_count = bvh.triangle_count;
            push.slot_count = slot_count;
            add_dispatch<shaders::smc_triangle_slots::Module>(passes, "smc triangle slots", pipeline, b, push,
                                                              std::max(bvh.triangle_count, 1u));
        }
        const auto& pipeline = smc_pipeline<shaders::smc_follow_surfaces::Pipeline>(device, bvh);
        auto b = smc_bindings<shaders::smc_follow_surfaces::Bindings>(scene, buffers);
        b.slots = buffers.triangle_slots.descriptor();
        shaders::smc_follow_surfaces::Push push{};
        push.budget = budget;
        push.triangle_count = bvh.triangle_count;
        push.slot_count = slot_count;
        add_dispatch<shaders::smc_follow_surfaces::Module>(passes, "smc follow surfaces", pipeline, b, push, budget);
    }
    {
        const auto& pipeline = smc_pipeline<shaders::smc_validate::Pipeline>(device, bvh);
        const auto b = smc_bindings<shaders::smc_validate::Bindings>(scene, buffers);
        shaders::smc_validate::Push push{};
        std::memcpy(&push.view_projection, &view.view_projection, sizeof(push.view_projection));
        push.camera_position = {view.position.x, view.position.y, view.position.z};
        push.budget = budget;
        push.surfaces_moved = change.geometry ? 1u : 0u;
        add_dispatch<shaders::smc_validate::Module>(passes, "smc validate", pipeline, b, push, push.budget);
    }
    {
        // The invalid VPLs in index order: which ones revalidate draws then depends on the seed alone.
        const auto& pipeline = smc_pipeline<shaders::smc_invalid_list::Pipeline>(device, bvh);
        add_budget_dispatch<shaders::smc_invalid_list::Module>(
            passes, "smc invalid list", pipeline, smc_bindings<shaders::smc_invalid_list::Bindings>(scene, buffers),
            budget, pipeline.workgroup_size[0]);  // one workgroup
    }
    for (uint32_t round = 0; round < options.visibility_rounds && options.visibility_tries > 0; ++round) {
        const auto& pipeline = smc_pipeline<shaders::smc_revalidate::Pipeline>(device, bvh);
        const auto b = smc_bindings<shaders::smc_revalidate::Bindings>(scene, buffers);
        shaders::smc_revalidate::Push push{};
        push.point_count = std::min(budget, pool);
        push.tries = options.visibility_tries;
        push.seed = options.seed;
        push.iteration = iteration;
        push.round = round;
        add_dispatch<shaders::smc_revalidate::Module>(passes, "smc revalidate", pipeline, b, push, push.point_count);
        // The round's winning claims become anchors before the next round reads valid[].
        add_budget_dispatch<shaders::smc_revalidate_claims::Module>(
            passes, "smc revalidate claims", smc_pipeline<shaders::smc_revalidate_claims::Pipeline>(device, bvh),
            smc_bindings<shaders::smc_revalidate_claims::Bindings>(scene, buffers), budget, budget);
    }

    sorter.add_pass(passes, buffers.pool_keys, buffers.pool_values, pool, "smc resample sort");
    {
        const auto& pipeline = smc_pipeline<shaders::smc_gather_candidates::Pipeline>(device, bvh);
        auto b = smc_bindings<shaders::smc_gather_candidates::Bindings>(scene, buffers);
        b.keys = buffers.pool_keys.descriptor();
        b.values = buffers.pool_values.descriptor();
        shaders::smc_gather_candidates::Push push{};
        push.budget = budget;
        push.pool_count = pool;
        push.seed = options.seed;
        push.iteration = iteration;
        add_dispatch<shaders::smc_gather_candidates::Module>(passes, "smc gather candidates", pipeline, b, push,
                                                             push.budget);
    }
    if (change.geometry || change.lights) add_radiosity_pass(buffers.state, RadiosityOf::every_vpl);
    add_radiosity_pass(buffers.candidates, RadiosityOf::candidates);
    add_smc_density_pass(device, passes, bvh, buffers.state, buffers.candidates, buffers.candidate_density, counters,
                         budget, 1, false, 0);
    {
        add_budget_dispatch<shaders::smc_selection_keys::Module>(
            passes, "smc selection keys", smc_pipeline<shaders::smc_selection_keys::Pipeline>(device, bvh),
            smc_bindings<shaders::smc_selection_keys::Bindings>(scene, buffers), budget, budget);
    }
    sorter.add_pass(passes, buffers.vpl_keys, buffers.vpl_values, budget, "smc vpl intensity sort");
    sorter.add_pass(passes, buffers.candidate_keys, buffers.candidate_values, budget, "smc candidate intensity sort");
    {
        const auto& pipeline = smc_pipeline<shaders::smc_select::Pipeline>(device, bvh);
        const auto b = smc_bindings<shaders::smc_select::Bindings>(scene, buffers);
        shaders::smc_select::Push push{};
        push.budget = budget;
        push.max_moves = options.max_moves;
        push.quantile = options.strong_quantile;
        add_dispatch<shaders::smc_select::Module>(passes, "smc select", pipeline, b, push, 1u);
    }
    {
        add_budget_dispatch<shaders::smc_replace::Module>(
            passes, "smc replace", smc_pipeline<shaders::smc_replace::Pipeline>(device, bvh),
            smc_bindings<shaders::smc_replace::Bindings>(scene, buffers), budget, budget);
    }
    add_radiosity_pass(buffers.state, RadiosityOf::moved_vpls);
    add_smc_density_pass(device, passes, bvh, buffers.state, buffers.state, buffers.vpl_density, counters, budget,
                         smc_render_neighbours(budget), true, options.surface_samples);
    {
        auto b = smc_bindings<shaders::smc_vpls::Bindings>(scene, buffers);
        b.density = buffers.vpl_density.descriptor();
        add_budget_dispatch<shaders::smc_vpls::Module>(
            passes, "smc vpls", smc_pipeline<shaders::smc_vpls::Pipeline>(device, bvh), b, budget, budget);
    }
}

}  // namespace vplkit::stages
