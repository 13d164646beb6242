#include "vplkit/stages/denoise.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/atrous.hpp"
#include "vplkit/shaders/atrous_variance.hpp"
#include "vplkit/shaders/atrous_weights.hpp"
#include "vplkit/shaders/demodulate.hpp"
#include "vplkit/shaders/firefly_clamp.hpp"
#include "vplkit/shaders/firefly_spread.hpp"
#include "vplkit/shaders/remodulate.hpp"
#include "vplkit/shaders/temporal_accumulate.hpp"
#include "vplkit/shaders/variance_estimate.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/gbuffer_views.hpp"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace vplkit::stages {

namespace {

// Every image of a pass: its format, and the size of the first.
void validate_images(const char* stage, const std::vector<std::pair<const ImageView*, VkFormat>>& images) {
    const ImageView& first = *images.front().first;
    for (const auto& [image, format] : images) {
        if (!*image) {
            throw Error(std::string(stage) + ": image '" + image->name + "' is missing");
        }
        if (image->format != format || image->width != first.width || image->height != first.height) {
            throw Error(std::string(stage) + ": image '" + image->name + "' must be " +
                        (format == VK_FORMAT_R32G32B32A32_SFLOAT ? "RGBA32F" : "RGBA16F") + " and " +
                        std::to_string(first.width) + "x" + std::to_string(first.height) + " like '" + first.name +
                        "'");
        }
    }
}

constexpr VkFormat kFloat4 = VK_FORMAT_R32G32B32A32_SFLOAT;

void check(bool ok, const std::string& what) {
    if (!ok) {
        throw Error("denoise: " + what);
    }
}

}  // namespace

void validate(const DenoiseOptions& o) {
    auto finite_non_negative = [](float v) { return std::isfinite(v) && v >= 0.0f; };
    check(std::isfinite(o.albedo_floor) && o.albedo_floor > 0.0f,
          "albedo_floor " + std::to_string(o.albedo_floor) + " must be > 0 (demodulation divides by it)");
    check(finite_non_negative(o.firefly_k_sigma),
          "firefly_k_sigma " + std::to_string(o.firefly_k_sigma) + " must be >= 0 (0: no clamp)");
    check(o.max_history >= 1, "max_history must be at least 1");
    check(std::isfinite(o.scene_scale) && o.scene_scale > 0.0f,
          "scene_scale " + std::to_string(o.scene_scale) + " must be a positive finite number");
    check(std::isfinite(o.max_plane_distance_fraction) && o.max_plane_distance_fraction > 0.0f,
          "max_plane_distance_fraction must be > 0");
    check(std::isfinite(o.min_normal_cos) && o.min_normal_cos >= -1.0f && o.min_normal_cos <= 1.0f,
          "min_normal_cos " + std::to_string(o.min_normal_cos) + " must be in [-1, 1]");
    check(std::isfinite(o.sigma_plane_fraction) && o.sigma_plane_fraction > 0.0f, "sigma_plane_fraction must be > 0");
    check(finite_non_negative(o.sigma_normal), "sigma_normal must be >= 0");
    check(std::isfinite(o.sigma_luminance) && o.sigma_luminance > 0.0f, "sigma_luminance must be > 0");
    check(o.atrous_iterations <= 10, "atrous_iterations " + std::to_string(o.atrous_iterations) +
                                         " must be at most 10 (step 2^9 is wider than any image it helps)");
}

void add_demodulate_pass(Device& device, StepList& passes, const ImageView& radiance, const ImageView& albedo,
                         const ImageView& position, const ImageView& irradiance, const DenoiseOptions& options) {
    validate(options);
    validate_images(
        "denoise demodulate",
        {{&irradiance, kFloat4}, {&radiance, kFloat4}, {&albedo, kGbufferAlbedoFormat}, {&position, kFloat4}});
    const auto& pipeline = device.pipeline<shaders::demodulate::Pipeline>();
    shaders::demodulate::Bindings b;
    b.radiance = radiance.descriptor();
    b.albedo = albedo.descriptor();
    b.position = position.descriptor();
    b.irradiance = irradiance.descriptor();
    shaders::demodulate::Push push{};
    push.albedo_floor = options.albedo_floor;
    add_dispatch<shaders::demodulate::Module>(passes, "denoise demodulate", pipeline, b, push,
                                              {irradiance.width, irradiance.height},
                                              {radiance, albedo, position, irradiance});
}

void add_remodulate_pass(Device& device, StepList& passes, const ImageView& irradiance, const ImageView& albedo,
                         const ImageView& radiance, const DenoiseOptions& options) {
    validate(options);
    validate_images("denoise remodulate",
                    {{&radiance, kFloat4}, {&irradiance, kFloat4}, {&albedo, kGbufferAlbedoFormat}});
    const auto& pipeline = device.pipeline<shaders::remodulate::Pipeline>();
    shaders::remodulate::Bindings b;
    b.irradiance = irradiance.descriptor();
    b.albedo = albedo.descriptor();
    b.radiance = radiance.descriptor();
    shaders::remodulate::Push push{};
    push.albedo_floor = options.albedo_floor;
    add_dispatch<shaders::remodulate::Module>(passes, "denoise remodulate", pipeline, b, push,
                                              {radiance.width, radiance.height}, {irradiance, albedo, radiance});
}

void add_firefly_clamp_passes(Device& device, StepList& passes, const ImageView& irradiance, const ImageView& moments,
                              const ImageView& albedo, const ImageView& position, const ImageView& clamped,
                              const ImageView& excess, const ImageView& spread, const DenoiseOptions& options) {
    validate(options);
    validate_images("denoise firefly clamp", {{&clamped, kFloat4},
                                              {&irradiance, kFloat4},
                                              {&position, kFloat4},
                                              {&moments, kFloat4},
                                              {&albedo, kGbufferAlbedoFormat},
                                              {&excess, kFloat4},
                                              {&spread, kFloat4}});
    const auto& clamp = device.pipeline<shaders::firefly_clamp::Pipeline>();
    shaders::firefly_clamp::Bindings b;
    b.irradiance = irradiance.descriptor();
    b.position = position.descriptor();
    b.clamped = clamped.descriptor();
    b.excess = excess.descriptor();
    b.albedo = albedo.descriptor();
    b.moments = moments.descriptor();
    shaders::firefly_clamp::Push push{};
    push.k_sigma = options.firefly_k_sigma;
    push.albedo_floor = options.albedo_floor;
    push.min_history = options.min_temporal_history;
    add_dispatch<shaders::firefly_clamp::Module>(passes, "denoise firefly clamp", clamp, b, push,
                                                 {clamped.width, clamped.height},
                                                 {irradiance, position, clamped, excess, albedo, moments});
    const auto& gather = device.pipeline<shaders::firefly_spread::Pipeline>();
    shaders::firefly_spread::Bindings g;
    g.clamped = clamped.descriptor();
    g.excess = excess.descriptor();
    g.position = position.descriptor();
    g.spread = spread.descriptor();
    g.albedo = albedo.descriptor();
    shaders::firefly_spread::Push spread_push{};
    spread_push.albedo_floor = options.albedo_floor;
    add_dispatch<shaders::firefly_spread::Module>(passes, "denoise firefly spread", gather, g, spread_push,
                                                  {spread.width, spread.height},
                                                  {clamped, excess, position, spread, albedo});
}

void add_temporal_accumulate_pass(Device& device, StepList& passes, const ImageView& irradiance,
                                  const ImageView& position, const ImageView& normal, const DenoiseHistory& previous,
                                  const DenoiseHistory& next, const ImageView& accumulated, const ImageView& moments,
                                  const glm::mat4& previous_view_projection, bool has_history,
                                  const DenoiseOptions& options, const ImageView& motion) {
    validate(options);
    const bool moved = bool(motion);
    if (moved) validate_images("denoise temporal", {{&position, kFloat4}, {&motion, kGbufferMotionFormat}});
    validate_images("denoise temporal", {{&accumulated, kFloat4},
                                         {&moments, kFloat4},
                                         {&irradiance, kFloat4},
                                         {&position, kFloat4},
                                         {&normal, kFloat4},
                                         {&previous.position, kFloat4},
                                         {&previous.normal, kFloat4},
                                         {&previous.color, kFloat4},
                                         {&previous.moments, kFloat4},
                                         {&next.position, kFloat4},
                                         {&next.normal, kFloat4}});
    const auto& pipeline = device.pipeline<shaders::temporal_accumulate::Pipeline>();
    shaders::temporal_accumulate::Bindings b;
    b.irradiance = irradiance.descriptor();
    b.position = position.descriptor();
    b.normal = normal.descriptor();
    b.previous_position = previous.position.descriptor();
    b.previous_normal = previous.normal.descriptor();
    b.previous_color = previous.color.descriptor();
    b.previous_moments = previous.moments.descriptor();
    b.accumulated = accumulated.descriptor();
    b.moments = moments.descriptor();
    b.history_position = next.position.descriptor();
    b.history_normal = next.normal.descriptor();
    // Without motion the position stands in for it (never read: has_motion 0).
    const ImageView& motion_or_position = moved ? motion : position;
    b.motion = motion_or_position.descriptor();
    shaders::temporal_accumulate::Push push{};
    static_assert(sizeof(push.previous_view_projection) == sizeof(glm::mat4));
    std::memcpy(&push.previous_view_projection, &previous_view_projection, sizeof(glm::mat4));
    push.max_plane_distance = options.max_plane_distance_fraction * options.scene_scale;
    push.min_normal_cos = options.min_normal_cos;
    push.max_history = options.max_history;
    push.has_history = has_history ? 1u : 0u;
    push.static_max_history = options.static_max_history;
    push.has_motion = moved ? 1u : 0u;
    add_dispatch<shaders::temporal_accumulate::Module>(
        passes, "denoise temporal", pipeline, b, push, {accumulated.width, accumulated.height},
        {irradiance, position, normal, previous.position, previous.normal, previous.color, previous.moments,
         accumulated, moments, next.position, next.normal, motion_or_position});
}

void add_variance_estimate_pass(Device& device, StepList& passes, const ImageView& accumulated,
                                const ImageView& moments, const ImageView& position, const ImageView& normal,
                                const ImageView& estimated, const DenoiseOptions& options) {
    validate(options);
    validate_images("denoise variance", {{&estimated, kFloat4},
                                         {&accumulated, kFloat4},
                                         {&moments, kFloat4},
                                         {&position, kFloat4},
                                         {&normal, kFloat4}});
    const auto& pipeline = device.pipeline<shaders::variance_estimate::Pipeline>();
    shaders::variance_estimate::Bindings b;
    b.accumulated = accumulated.descriptor();
    b.moments = moments.descriptor();
    b.position = position.descriptor();
    b.normal = normal.descriptor();
    b.estimated = estimated.descriptor();
    shaders::variance_estimate::Push push{};
    push.sigma_plane = options.sigma_plane_fraction * options.scene_scale;
    push.sigma_normal = options.sigma_normal;
    push.min_history = options.min_temporal_history;
    add_dispatch<shaders::variance_estimate::Module>(passes, "denoise variance", pipeline, b, push,
                                                     {estimated.width, estimated.height},
                                                     {accumulated, moments, position, normal, estimated});
}

void add_atrous_passes(Device& device, StepList& passes, const ImageView& source, const ImageView& position,
                       const ImageView& normal, const AtrousScratch& scratch, const ImageView& filtered, int step,
                       const DenoiseOptions& options) {
    validate(options);
    check(step >= 1, "a-trous step " + std::to_string(step) + " must be at least 1");
    validate_images("denoise a-trous", {{&filtered, kFloat4},
                                        {&source, kFloat4},
                                        {&position, kFloat4},
                                        {&normal, kFloat4},
                                        {&scratch.variance, kFloat4},
                                        {&scratch.weights, kFloat4}});
    for (const ImageView* s : {&scratch.variance, &scratch.weights}) {
        check(s->image != source.image && s->image != filtered.image,
              "a-trous scratch image '" + s->name + "' is also its source or output");
    }
    check(scratch.variance.image != scratch.weights.image, "the a-trous scratch images must be two images");
    const std::string suffix = std::to_string(step);
    {
        const auto& pipeline = device.pipeline<shaders::atrous_variance::Pipeline>();
        shaders::atrous_variance::Bindings b;
        b.source = source.descriptor();
        b.position = position.descriptor();
        b.blurred_variance = scratch.variance.descriptor();
        add_dispatch<shaders::atrous_variance::Module>(passes, "denoise a-trous variance " + suffix, pipeline, b,
                                                       {filtered.width, filtered.height},
                                                       {source, position, scratch.variance});
    }
    {
        const auto& pipeline = device.pipeline<shaders::atrous_weights::Pipeline>();
        shaders::atrous_weights::Bindings b;
        b.source = source.descriptor();
        b.position = position.descriptor();
        b.normal = normal.descriptor();
        b.blurred_variance = scratch.variance.descriptor();
        b.weights = scratch.weights.descriptor();
        shaders::atrous_weights::Push push{};
        push.step = step;
        push.sigma_plane = options.sigma_plane_fraction * options.scene_scale;
        push.sigma_normal = options.sigma_normal;
        push.sigma_luminance = options.sigma_luminance;
        add_dispatch<shaders::atrous_weights::Module>(passes, "denoise a-trous weights " + suffix, pipeline, b, push,
                                                      {filtered.width, filtered.height},
                                                      {source, position, normal, scratch.variance, scratch.weights});
    }
    const auto& pipeline = device.pipeline<shaders::atrous::Pipeline>();
    shaders::atrous::Bindings b;
    b.source = source.descriptor();
    b.position = position.descriptor();
    b.normal = normal.descriptor();
    b.weights = scratch.weights.descriptor();
    b.filtered = filtered.descriptor();
    shaders::atrous::Push push{};
    push.step = step;
    push.sigma_plane = options.sigma_plane_fraction * options.scene_scale;
    push.sigma_normal = options.sigma_normal;
    push.sigma_luminance = options.sigma_luminance;
    add_dispatch<shaders::atrous::Module>(passes, "denoise a-trous " + suffix, pipeline, b, push,
                                          {filtered.width, filtered.height},
                                          {source, position, normal, scratch.weights, filtered});
}

}  // namespace vplkit::stages
