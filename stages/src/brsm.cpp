#include "vplkit/stages/brsm.hpp"

#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/brsm_contribution.hpp"
#include "vplkit/shaders/brsm_filter.hpp"
#include "vplkit/shaders/brsm_importance.hpp"
#include "vplkit/shaders/brsm_vpl_count.hpp"
#include "vplkit/shaders/brsm_vpls.hpp"
#include "vplkit/stages/importance_warp.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>

namespace vplkit::stages {

namespace {

constexpr uint32_t kMaxSamplesPerTexel = 1024;
constexpr uint32_t kMaxFilterRadius = 8;

[[noreturn]] void bad_option(const std::string& what) {
    throw Error("BRSM: " + what);
}

bool in_open_range(float v, float lo, float hi) {
    return std::isfinite(v) && v > lo && v < hi;
}

}  // namespace

void validate(const BrsmOptions& o) {
    if (o.vpl_count == 0) bad_option("vpl_count is 0");
    if (o.samples_per_texel == 0 || o.samples_per_texel > kMaxSamplesPerTexel) {
        bad_option("samples_per_texel " + std::to_string(o.samples_per_texel) + " is not in 1.." +
                   std::to_string(kMaxSamplesPerTexel));
    }
    if (!in_open_range(o.core_radius, 0.0f, INFINITY)) bad_option("core_radius must be a positive number");
    if (!in_open_range(o.max_radius, o.core_radius, INFINITY)) bad_option("max_radius must be above core_radius");
    if (!in_open_range(o.filter_sigma, 0.0f, INFINITY)) bad_option("filter_sigma must be a positive number");
    if (o.filter_radius > kMaxFilterRadius) {
        bad_option("filter_radius " + std::to_string(o.filter_radius) + " is above " +
                   std::to_string(kMaxFilterRadius));
    }
    if (!std::isfinite(o.similarity_min_cos) || o.similarity_min_cos < -1.0f || o.similarity_min_cos >= 1.0f) {
        bad_option("similarity_min_cos must be in [-1, 1)");
    }
    if (!in_open_range(o.similarity_max_distance, 0.0f, INFINITY)) {
        bad_option("similarity_max_distance must be a positive number");
    }
    if (!std::isfinite(o.defensive_fraction) || o.defensive_fraction < 0.0f || o.defensive_fraction > 1.0f) {
        bad_option("defensive_fraction must be in [0, 1]");
    }
}

BrsmLightRequirements brsm_light_requirements(uint32_t map_width, uint32_t map_height, uint32_t vpl_share) {
    if (map_width == 0 || map_height == 0) throw Error("BRSM: a shadow map of zero size");
    BrsmLightRequirements r;
    r.map_size = std::bit_ceil(std::max(map_width, map_height));
    if (vpl_share == 0) return r;
    r.contribution_bytes = uint64_t(r.map_size) * r.map_size * sizeof(float);
    r.mip_chain_bytes = importance_mip_floats(r.map_size) * sizeof(float);
    r.samples_bytes = uint64_t(vpl_share) * sizeof(shaders::WarpedSample);
    r.warp_count_bytes = sizeof(shaders::WarpCountBuffer);
    return r;
}

namespace {

// The passes of one light, up to and including its VPLs and the count that follows them.
// Views are captured by value: the caller's may be temporaries that are gone when the steps are
// recorded.
void add_light_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const CameraView& view,
                      const ShadowMapViews& map, float scene_scale, const BrsmOptions& options, uint32_t seed,
                      const BrsmLightViews& light, const BrsmOutputViews& output) {
    const ImageView rsm_position = map.position, rsm_normal = map.normal, rsm_flux = map.flux;
    const BufferView vpl_buffer = output.vpls, vpl_count = output.count;
    const uint32_t size = light.map_size;
    const uint32_t top = uint32_t(importance_top_offset(size));

    const auto& contribution = device.pipeline<shaders::brsm_contribution::Pipeline>();
    shaders::brsm_contribution::Push contribution_push{};
    std::memcpy(&contribution_push.camera_view_projection, &view.view_projection,
                sizeof(contribution_push.camera_view_projection));
    contribution_push.map_size = size;
    contribution_push.sample_count = options.samples_per_texel;
    contribution_push.seed = seed;
    contribution_push.core_radius = options.core_radius * scene_scale;
    contribution_push.max_radius = options.max_radius * scene_scale;
    contribution_push.scene_scale = scene_scale;
    shaders::brsm_contribution::Bindings contribution_bindings;
    contribution_bindings.rsm_position = rsm_position.descriptor();
    contribution_bindings.rsm_normal = rsm_normal.descriptor();
    contribution_bindings.rsm_flux = rsm_flux.descriptor();
    contribution_bindings.gbuffer_position = gbuffer.position.descriptor();
    contribution_bindings.gbuffer_normal = gbuffer.normal.descriptor();
    contribution_bindings.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
    contribution_bindings.gbuffer_albedo = gbuffer.albedo.descriptor();
    contribution_bindings.contribution = light.contribution.descriptor();
    contribution_bindings.flux_luminance = light.flux_mips.descriptor();
    add_dispatch(passes, "brsm contribution",
                 {Use::read(map.position), Use::read(map.normal), Use::read(map.flux), Use::read(gbuffer.position),
                  Use::read(gbuffer.normal), Use::read(gbuffer.geometric_normal), Use::read(gbuffer.albedo),
                  Use::write(light.contribution), Use::write(light.flux_mips)},
                 contribution, contribution_bindings, contribution_push,
                 {contribution_push.map_size, contribution_push.map_size});

    shaders::brsm_filter::Spec filter_spec;
    filter_spec.kFilterRadius = int32_t(options.filter_radius);
    const auto& filter = device.pipeline<shaders::brsm_filter::Pipeline>(filter_spec);
    shaders::brsm_filter::Push filter_push{};
    filter_push.map_size = size;
    filter_push.sigma = options.filter_sigma;
    filter_push.min_cos = options.similarity_min_cos;
    filter_push.max_distance = options.similarity_max_distance * scene_scale;
    shaders::brsm_filter::Bindings filter_bindings;
    filter_bindings.rsm_position = rsm_position.descriptor();
    filter_bindings.rsm_normal = rsm_normal.descriptor();
    filter_bindings.contribution = light.contribution.descriptor();
    filter_bindings.flux_luminance = light.flux_mips.descriptor();
    filter_bindings.filtered = light.contribution_mips.descriptor();
    add_dispatch(passes, "brsm filter",
                 {Use::read(map.position), Use::read(map.normal), Use::read(light.contribution),
                  Use::read(light.flux_mips), Use::write(light.contribution_mips)},
                 filter, filter_bindings, filter_push, {filter_push.map_size, filter_push.map_size});

    add_importance_mip_levels_passes(device, passes, light.contribution_mips, size);
    add_importance_mip_levels_passes(device, passes, light.flux_mips, size);

    const auto& importance = device.pipeline<shaders::brsm_importance::Pipeline>();
    shaders::brsm_importance::Push importance_push{};
    importance_push.texel_count = size * size;
    importance_push.top_offset = top;
    importance_push.defensive_fraction = options.defensive_fraction;
    shaders::brsm_importance::Bindings importance_bindings;
    importance_bindings.contribution = light.contribution_mips.descriptor();
    importance_bindings.flux = light.flux_mips.descriptor();
    importance_bindings.importance = light.importance_mips.descriptor();
    add_dispatch(passes, "brsm importance",
                 {Use::read(light.contribution_mips), Use::read(light.flux_mips), Use::write(light.importance_mips)},
                 importance, importance_bindings, importance_push, importance_push.texel_count);
    add_importance_mip_levels_passes(device, passes, light.importance_mips, size);
    add_warp_samples_pass(device, passes, light.importance_mips, light.samples, light.warp_count, size, light.vpl_share,
                          seed);

    const auto& vpls = device.pipeline<shaders::brsm_vpls::Pipeline>();
    shaders::brsm_vpls::Push vpls_push{};
    vpls_push.sample_count = light.vpl_share;
    vpls_push.map_size = size;
    vpls_push.capacity = output.capacity;
    shaders::brsm_vpls::Bindings vpls_bindings;
    vpls_bindings.rsm_position = rsm_position.descriptor();
    vpls_bindings.rsm_normal = rsm_normal.descriptor();
    vpls_bindings.rsm_flux = rsm_flux.descriptor();
    vpls_bindings.samples = light.samples.descriptor();
    vpls_bindings.warp = light.warp_count.descriptor();
    vpls_bindings.vpl_count = vpl_count.descriptor();
    vpls_bindings.vpls = vpl_buffer.descriptor();
    add_dispatch(passes, "brsm vpls",
                 {Use::read(map.position), Use::read(map.normal), Use::read(map.flux), Use::read(light.samples),
                  Use::read(light.warp_count), Use::read(output.count), Use::write(output.vpls)},
                 vpls, vpls_bindings, vpls_push, vpls_push.sample_count);

    const auto& count = device.pipeline<shaders::brsm_vpl_count::Pipeline>();
    shaders::brsm_vpl_count::Push count_push{};
    count_push.sample_count = light.vpl_share;
    shaders::brsm_vpl_count::Bindings count_bindings;
    count_bindings.warp = light.warp_count.descriptor();
    count_bindings.vpl_count = vpl_count.descriptor();
    add_dispatch(passes, "brsm vpl count", {Use::read(light.warp_count), Use::read_write(output.count)}, count,
                 count_bindings, count_push, 1);
}

}  // namespace

void add_brsm_count_clear_pass(StepList& passes, const BrsmOutputViews& output) {
    const BufferView count = output.count;  // by value: `output` may be a temporary
    passes.add("brsm count clear", {Use::transfer_dst(count)}, [count](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, count.buffer, count.offset, sizeof(shaders::VplCountBuffer), 0u);
    });
}

void add_brsm_light_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const CameraView& view,
                           const ShadowMapViews& map, size_t light_index, float scene_scale, const BrsmOptions& options,
                           const BrsmOutputViews& output) {
    validate(options);
    if (light_index >= output.lights.size()) {
        throw Error("BRSM: light " + std::to_string(light_index) + ", but the output was created for " +
                    std::to_string(output.lights.size()));
    }
    if (!(scene_scale > 0.0f) || !std::isfinite(scene_scale)) throw Error("BRSM: scene_scale must be positive");
    const BrsmLightViews& light = output.lights[light_index];
    if (light.vpl_share == 0) return;
    if (std::bit_ceil(std::max(map.width(), map.height())) != light.map_size) {
        throw Error("BRSM: light " + std::to_string(light_index) +
                    "'s buffers were not allocated for this map (allocate_brsm_light_buffers)");
    }
    // Each light its own streams (the Hammersley rotation and the contribution samples would
    // otherwise repeat from light to light); light 0 keeps the seed itself.
    const uint32_t light_seed = options.seed ^ (0x9e3779b9u * uint32_t(light_index));
    add_light_passes(device, passes, gbuffer, view, map, scene_scale, options, light_seed, light, output);
}

void add_brsm_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const CameraView& view,
                     std::span<const ShadowMapViews> maps, float scene_scale, const BrsmOptions& options,
                     const BrsmOutputViews& output) {
    if (maps.size() != output.lights.size()) {
        throw Error("BRSM: " + std::to_string(maps.size()) + " maps, but the output was created for " +
                    std::to_string(output.lights.size()));
    }
    add_brsm_count_clear_pass(passes, output);
    for (size_t i = 0; i < maps.size(); ++i) {
        add_brsm_light_passes(device, passes, gbuffer, view, maps[i], i, scene_scale, options, output);
    }
}

}  // namespace vplkit::stages
