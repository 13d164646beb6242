#include "vplkit/planner.hpp"

#include "vplkit/gi_methods.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/glossy_lobe.hpp"
#include "vplkit/stages/rtslc.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace vplkit {

const char* stage_name(FrameStage stage) {
    switch (stage) {
        case FrameStage::gbuffer:
            return "gbuffer";
        case FrameStage::direct_light:
            return "direct light";
        case FrameStage::direct_emissive:
            return "direct emissive";
        case FrameStage::direct_tree:
            return "direct tree";
        case FrameStage::vpl_paths:
            return "vpl paths";
        case FrameStage::brsm_vpls:
            return "brsm vpls";
        case FrameStage::smc_vpls:
            return "smc vpls";
        case FrameStage::flc_vpls:
            return "flc vpls";
        case FrameStage::vpl_sort:
            return "vpl sort";
        case FrameStage::light_tree:
            return "light tree";
        case FrameStage::sst:
            return "sst";
        case FrameStage::gi_downsample:
            return "gi downsample";
        case FrameStage::gi_exact:
            return "gi exact";
        case FrameStage::gi_sst:
            return "gi sst";
        case FrameStage::gi_rtslc:
            return "gi rtslc";
        case FrameStage::gi_hybrid:
            return "gi hybrid";
        case FrameStage::gi_flc:
            return "gi flc";
        case FrameStage::gi_upsample:
            return "gi upsample";
        case FrameStage::denoise:
            return "denoise";
        case FrameStage::compose:
            return "compose";
        case FrameStage::tonemap:
            return "tonemap";
    }
    return "?";
}

bool FramePlan::runs(FrameStage stage) const {
    for (const PlannedStage& s : stages) {
        if (s.stage == stage) return s.runs;
    }
    return false;
}

std::string FramePlan::summary() const {
    std::string kept, out;
    for (const PlannedStage& s : stages) {
        std::string& list = s.runs ? kept : out;
        list += (list.empty() ? "" : ", ") + std::string(stage_name(s.stage));
    }
    return "plan: " + kept + (out.empty() ? "" : "; left out: " + out) + (glossy_branch ? "; glossy branch on" : "");
}

std::string FramePlan::describe() const {
    std::ostringstream s;
    for (const PlannedStage& p : stages) {
        s << (p.runs ? "  run   " : "  skip  ") << stage_name(p.stage) << ": " << p.reason << "\n";
    }
    s << (glossy_branch ? "  on    " : "  off   ") << "glossy branch: " << glossy_reason << "\n";
    for (const std::string& note : notes) s << "note: " << note << "\n";
    return s.str();
}

const char* direct_sampler_name(DirectSampler sampler) {
    switch (sampler) {
        case DirectSampler::flat:
            return "flat";
        case DirectSampler::tree:
            return "tree";
        case DirectSampler::tree2:
            return "tree2";
        case DirectSampler::automatic:
            return "auto";
    }
    return "?";
}

std::vector<GlossyMaterial> glossy_materials(const scene::Scene& scene, float max_roughness) {
    std::vector<GlossyMaterial> out;
    for (const scene::Material& m : scene.materials) {
        if (m.roughness_factor < 0.0f) continue;  // Lambertian (scene::use_lambertian_materials)
        float texel = 1.0f;                       // the smallest roughness the texture holds
        if (m.metallic_roughness_texture != scene::kNoTexture) {
            const scene::Image& image = scene.images.at(scene.textures.at(m.metallic_roughness_texture).image);
            uint8_t smallest = 255;
            for (size_t i = 1; i < image.rgba.size(); i += 4) smallest = std::min(smallest, image.rgba[i]);
            texel = smallest / 255.0f;
        }
        const float min_roughness = m.roughness_factor * texel;
        if (min_roughness < max_roughness) out.push_back({m.name, min_roughness});
    }
    return out;
}

namespace {

// "forced on (...)", or which materials can be smoother than the limit, or that none can.
std::string glossy_branch_reason(const scene::Scene& scene, const RenderSettings& settings, bool sampled, bool& on) {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%.2g", stages::kGlossyMaxRoughness);
    on = false;
    if (!sampled) {
        const GiMethodInfo& method = gi_method(settings.method);
        return method.ground_truth ? std::string(method.no_tree) + ": no tree traversal to steer"
                                   : "no tree sampling method";
    }
    if (settings.glossy_branch == GlossyBranch::off) return "forced off (`glossy_branch` off)";
    if (settings.glossy_branch == GlossyBranch::on || settings.force_all_stages) {
        on = true;
        return settings.glossy_branch == GlossyBranch::on ? "forced on (`glossy_branch` on)"
                                                          : "forced on (`force_all_stages`)";
    }
    const auto glossy = glossy_materials(scene, stages::kGlossyMaxRoughness);
    if (glossy.empty()) return std::string("no material smoother than roughness ") + limit + ": compiled out";
    on = true;
    std::ostringstream s;
    s.precision(2);
    s << glossy.size() << " material(s) can be smoother than roughness " << limit << ":";
    const size_t shown = std::min<size_t>(glossy.size(), 4);
    for (size_t i = 0; i < shown; ++i) {
        s << (i ? ", '" : " '") << glossy[i].name << "' (" << glossy[i].min_roughness << ")";
    }
    if (glossy.size() > shown) s << " and " << glossy.size() - shown << " more";
    return s.str();
}

}  // namespace

std::string vpl_set_key(const RenderSettings& settings, VplSource source, const std::string& view_key) {
    std::ostringstream key;
    key.precision(9);
    if (source == VplSource::brsm) {
        // View-dependent: BRSM places VPLs where this camera sees their light.
        key << "brsm " << settings.brsm.vpl_count << ' ' << settings.brsm.samples_per_texel << ' '
            << settings.brsm.core_radius << ' ' << settings.brsm.max_radius << ' ' << settings.brsm.filter_sigma << ' '
            << settings.brsm.filter_radius << ' ' << settings.brsm.similarity_min_cos << ' '
            << settings.brsm.similarity_max_distance << ' ' << settings.brsm.defensive_fraction << ' '
            << settings.rsm_resolution << " seed " << settings.seed << " view " << view_key;
    } else if (source == VplSource::smc) {
        // The options of the persistent set; plan_frame never reuses an SMC set (it moves every frame).
        const stages::SmcOptions& o = settings.smc;
        key << "smc " << o.budget << ' ' << o.max_moves << ' ' << o.resample_ratio << ' ' << o.radiosity_samples << ' '
            << o.bounces << ' ' << o.visibility_tries << ' ' << o.visibility_rounds << ' ' << o.strong_quantile
            << " warmup " << settings.smc_warmup << " seed " << settings.seed;
    } else {
        // Light paths do not depend on the camera.
        key << "ir " << settings.vpl_paths << ' ' << settings.vpl_bounces << " seed " << settings.seed;
    }
    return key.str();
}

std::string tree_settings_key(const RenderSettings& settings) {
    std::ostringstream key;
    key.precision(9);
    key << "sst " << settings.sst.nu_min << ' ' << settings.sst.sigma_max;
    return key.str();
}

namespace {

// "geometry moved", "lights moved", "geometry and lights moved" between two poses ("" when none).
std::string moved_between(const SceneVersion& before, const SceneVersion& now) {
    const bool geometry = before.geometry != now.geometry, lights = before.lights != now.lights;
    return geometry && lights ? "geometry and lights moved"
           : geometry         ? "geometry moved"
           : lights           ? "lights moved"
                              : "";
}

}  // namespace

FramePlan plan_frame(const scene::Scene& scene, const RenderSettings& settings, const std::string& view_key,
                     const ReusableWork& previous, const SceneVersion& now) {
    FramePlan plan;
    const bool punctual = !scene.lights.empty();
    const bool emissive = !scene.emissive_triangles.empty();
    const bool lit = punctual || emissive;
    const GiMethodInfo& method = gi_method(settings.method);
    const bool indirect = method.vpls != GiVpls::none || settings.vpls_only;
    const bool sampled = method.samples;
    const bool half = settings.half_resolution_gi && method.vpls != GiVpls::none && !settings.vpls_only;
    // A method that places its own VPLs (flc: one per kept triangle) uses no VPL source.
    const bool own_vpls = method.vpls == GiVpls::own && !settings.vpls_only;
    auto add = [&plan](FrameStage stage, bool runs, std::string reason) {
        plan.stages.push_back({stage, runs, std::move(reason)});
    };

    if (!lit)
        plan.notes.push_back(
            "the scene has no light (no punctual light, no emissive triangle): the image would be black");

    // Which VPLs, if any.
    std::string source_reason;
    plan.vpl_source = settings.vpl_source;
    if (settings.vpl_source == VplSource::automatic) {
        if (settings.vpl_bounces == 1 && punctual && !emissive) {
            plan.vpl_source = VplSource::brsm;
            source_reason = "one bounce asked for: BRSM places first-bounce VPLs where the camera sees their light";
        } else {
            plan.vpl_source = VplSource::ir;
            source_reason = settings.vpl_bounces == 1
                                ? (emissive ? "one bounce, but BRSM has no VPLs for emissive triangles: light paths"
                                            : "one bounce, but BRSM needs a punctual light: light paths")
                                : "multi-bounce (" + std::to_string(settings.vpl_bounces) + " bounces): light paths";
        }
    } else {
        source_reason = plan.vpl_source == VplSource::brsm  ? "BRSM asked for"
                        : plan.vpl_source == VplSource::smc ? "SMC asked for: the set persists and moves at most " +
                                                                  std::to_string(settings.smc.max_moves) +
                                                                  " VPLs per frame; radiosities of surviving VPLs are "
                                                                  "kept, not re-estimated (static lights)"
                                                            : "light paths asked for";
    }
    plan.vpl_key = vpl_set_key(settings, plan.vpl_source, view_key);
    plan.tree_key = tree_settings_key(settings);
    // --all-stages: every stage that can run for this method does, nothing is reused (what the
    // planner saves is measured against this).
    const bool force = settings.force_all_stages;
    // An SMC set changes every frame by design (its update is the frame's VPL stage), so neither
    // it nor the trees over it are ever reused.
    // A pose that moved geometry or lights since the cached VPLs were made (same settings).
    const std::string vpls_moved = !previous.vpl_key.empty() && previous.vpl_key == plan.vpl_key
                                       ? moved_between(previous.vpl_scene, now)
                                       : std::string();
    plan.reuse_vpls = !force && settings.reuse_static_work && indirect && !own_vpls && lit &&
                      !previous.vpl_key.empty() && previous.vpl_key == plan.vpl_key && vpls_moved.empty() &&
                      plan.vpl_source != VplSource::smc;
    // Which tree the method reads, and which ones this frame builds (all of them when forced).
    const bool reads_light_tree = method.reads_light_tree;
    const bool reads_sst = method.reads_sst;
    const bool needs_light_tree = (reads_light_tree || (force && sampled)) && !settings.vpls_only;
    const bool needs_sst = (reads_sst || (force && sampled)) && !settings.vpls_only;
    plan.reuse_trees = plan.reuse_vpls && previous.tree_key == plan.tree_key &&
                       (!needs_light_tree || previous.light_tree) && (!needs_sst || previous.sst);

    add(FrameStage::gbuffer, true, "every frame: the surfaces the camera sees");
    // Direct light: the flat sampler or the light tree, and why.
    uint32_t directional = 0;
    for (const scene::Light& light : scene.lights) directional += light.type == scene::LightType::directional ? 1 : 0;
    const uint32_t positioned = uint32_t(scene.lights.size()) - directional;
    const uint32_t tree_lights = uint32_t(scene.emissive_triangles.size()) + positioned;
    const std::string counted = std::to_string(scene.emissive_triangles.size()) + " emissive triangle(s) and " +
                                std::to_string(positioned) + " point/spot light(s)";
    std::string sampler_reason;
    if (tree_lights == 0) {
        plan.direct_sampler = DirectSampler::flat;
        sampler_reason = "no emissive triangle, point or spot light: no light tree to build";
    } else if (settings.direct_sampler == DirectSampler::automatic &&
               settings.direct_samples > stages::kRtslcMaxSamplesPerPixel) {
        // The tree's cut holds at most 64 nodes, one sample each: more samples go to the flat sampler.
        plan.direct_sampler = DirectSampler::flat;
        sampler_reason = counted + ", but `direct_samples` " + std::to_string(settings.direct_samples) +
                         " is above the tree's " + std::to_string(stages::kRtslcMaxSamplesPerPixel) +
                         " samples per pixel, so emitters are drawn by power";
    } else if (settings.direct_sampler == DirectSampler::automatic) {
        plan.direct_sampler = tree_lights > kDirectTreeMinLights ? DirectSampler::tree : DirectSampler::flat;
        sampler_reason =
            counted + (plan.direct_sampler == DirectSampler::tree
                           ? ": more than " + std::to_string(kDirectTreeMinLights) +
                                 ", so one light tree samples them (cost per sample grows with log n, "
                                 "not n; near lights get the samples)"
                           : ": " + std::to_string(kDirectTreeMinLights) +
                                 " or fewer, so each point light is evaluated exactly and emitters "
                                 "are drawn by power (`direct_sampler` tree to sample them through the tree)");
    } else {
        plan.direct_sampler = settings.direct_sampler;
        sampler_reason = std::string("`direct_sampler` ") + direct_sampler_name(settings.direct_sampler) +
                         " asked for (" + counted + ")";
        if (plan.direct_sampler == DirectSampler::tree2) {
            sampler_reason +=
                ": two-level, a bottom tree per emitting primitive instance under a top tree over them "
                "(auto keeps one level: two levels measured no better, README)";
        }
    }
    const bool tree = plan.direct_sampler == DirectSampler::tree || plan.direct_sampler == DirectSampler::tree2;
    add(FrameStage::direct_light, true,
        tree ? "emission, background and " + std::to_string(directional) +
                   " directional light(s); the tree samples the rest"
        : punctual ? std::to_string(scene.lights.size()) + " punctual light(s), plus emission and background"
                   : "no punctual light: emission and background only");
    add(FrameStage::direct_emissive, !tree && (emissive || force),
        tree       ? "the light tree samples the emissive triangles: " + sampler_reason
        : emissive ? std::to_string(scene.emissive_triangles.size()) + " emissive triangles, flat: " + sampler_reason
        : force    ? "forced on (`force_all_stages`); no emissive triangle"
                   : "no emissive triangle");
    std::string tree_state;
    if (tree) {
        // The tree is over point and spot lights and emissive triangles: kept while they stay.
        const SceneVersion& built = previous.direct_tree_scene.value_or(now);
        const bool lights_moved = built.lights != now.lights && positioned > 0;
        const bool emitters_moved = built.geometry != now.geometry && emissive;
        plan.build_direct_tree = !previous.direct_tree_scene || lights_moved || emitters_moved;
        tree_state = !previous.direct_tree_scene      ? "; its tree built this frame (first use)"
                     : lights_moved && emitters_moved ? "; its tree rebuilt: lights and emissive geometry moved"
                     : lights_moved                   ? "; its tree rebuilt: lights moved"
                     : emitters_moved                 ? "; its tree rebuilt: emissive geometry moved"
                     : force                          ? "; its tree rebuilt (`force_all_stages`)"
                                                      : "; its tree reused: lights unchanged";
    }
    add(FrameStage::direct_tree, tree, tree ? sampler_reason + tree_state : "flat sampler: " + sampler_reason);

    const std::string reused = "reused: lights, geometry and VPL settings unchanged since the previous frame";
    const bool make_vpls = indirect && lit && !plan.reuse_vpls && !own_vpls;
    auto vpl_reason = [&](VplSource source) -> std::string {
        if (!indirect) return "direct light only (`method` " + std::string(method.name) + "): no VPLs";
        if (own_vpls) return std::string(method.name) + " places its own VPLs";
        if (!lit) return "no light to place VPLs from";
        if (plan.vpl_source != source) {
            return plan.vpl_source == VplSource::brsm  ? "BRSM places this frame's VPLs"
                   : plan.vpl_source == VplSource::smc ? "SMC updates this frame's VPLs"
                                                       : "light paths place this frame's VPLs";
        }
        if (plan.reuse_vpls) return reused;
        if (!vpls_moved.empty()) return source_reason + "; made again: " + vpls_moved + " since the cached VPLs";
        return source_reason;
    };
    add(FrameStage::vpl_paths, make_vpls && plan.vpl_source == VplSource::ir, vpl_reason(VplSource::ir));
    add(FrameStage::brsm_vpls, make_vpls && plan.vpl_source == VplSource::brsm, vpl_reason(VplSource::brsm));
    add(FrameStage::smc_vpls, make_vpls && plan.vpl_source == VplSource::smc, vpl_reason(VplSource::smc));
    const bool flc = own_vpls && settings.method == GiMethod::flc;  // flc's own VPL stage
    add(FrameStage::flc_vpls, flc && lit,
        flc ? (lit ? "read by flc: a VPL per kept triangle, lit by the direct light (the FLC paper sec. 4)"
                   : "no light to light VPLs with")
        : method.vpls == GiVpls::none ? "direct light only (`method` " + std::string(method.name) + "): no VPLs"
                                      : "`method` " + std::string(method.name));

    const bool build_trees = sampled && lit && !settings.vpls_only && !plan.reuse_trees;
    // `reads`: the method reads this tree; `built`: the frame builds it (read, or forced on).
    auto tree_reason = [&](bool reads, bool built, const char* what) -> std::string {
        if (!lit) return "no light: no VPLs to build a tree over";
        if (settings.vpls_only) return "VPLs only: no indirect light";
        if (!sampled) return std::string(method.no_tree) + ": no tree";
        if (!built) return "the " + std::string(method.name) + " method does not read " + what;
        if (plan.reuse_trees) return "reused: built over the same VPLs with the same settings last frame";
        if (!reads) return "forced on (`force_all_stages`); the method does not read it";
        if (plan.vpl_source == VplSource::smc) {
            return "read by " + std::string(method.name) + "; rebuilt every frame: the SMC set moves";
        }
        if (!vpls_moved.empty()) return "read by " + std::string(method.name) + "; rebuilt: " + vpls_moved;
        return "read by " + std::string(method.name);
    };
    add(FrameStage::vpl_sort, build_trees, tree_reason(true, true, "sorted leaves"));
    add(FrameStage::light_tree, build_trees && needs_light_tree,
        tree_reason(reads_light_tree, needs_light_tree, "the light tree"));
    add(FrameStage::sst, build_trees && needs_sst, tree_reason(reads_sst, needs_sst, "the SST"));

    const bool gi = method.stage && !settings.vpls_only && lit;
    const std::string no_gi = !method.stage ? "direct light only" : settings.vpls_only ? "VPLs only" : "no light";
    add(FrameStage::gi_downsample, gi && half,
        !gi    ? no_gi + ": no indirect light"
        : half ? "GI at half resolution"
               : "GI resolution equals the output: no half G-buffer");
    for (const GiMethodInfo& each : gi_methods()) {
        if (!each.stage) continue;
        const bool chosen = settings.method == each.method;
        std::string reason = "`method` " + std::string(method.name);
        if (chosen) {
            reason = settings.vpls_only ? "VPLs only: no indirect light"
                     : !lit             ? "no light: no indirect light"
                                        : "the method asked for";
        }
        add(*each.stage, gi && chosen, reason);
    }
    add(FrameStage::gi_upsample, gi && half,
        !gi    ? no_gi + ": no indirect light"
        : half ? "GI at half resolution"
               : "GI resolution equals the output: no upsampling");
    // The filter only where it can help: exact is the ground truth, and a temporal-only filter
    // without history has nothing to average (it still runs then, to start the history).
    const bool denoise = gi && settings.denoise != DenoiseMode::off && !method.ground_truth;
    // The filter follows moved geometry with the G-buffer's motion. Reprojected with the camera
    // alone, the history would drag moved objects' light along, so it is dropped then (moved
    // lights only lag: kept).
    const bool geometry_moved = previous.history_scene.geometry != now.geometry;
    plan.drop_denoise_history =
        denoise && previous.denoise_history && geometry_moved && settings.denoise_motion == DenoiseMotion::drop;
    const bool history = previous.denoise_history && !plan.drop_denoise_history;
    const bool follows_motion =
        denoise && history && geometry_moved && settings.denoise_motion == DenoiseMotion::follow;
    const std::string no_history = plan.drop_denoise_history ? "history dropped: geometry moved" : "no history yet";
    add(FrameStage::denoise, denoise,
        !gi                                    ? no_gi + ": nothing to filter"
        : settings.denoise == DenoiseMode::off ? "`denoise` off"
        : method.ground_truth                  ? std::string(method.name) + " is the ground truth: nothing to filter"
        : settings.denoise == DenoiseMode::svgf
            ? std::string("svgf: temporal accumulation and the a-trous filter") +
                  (!history         ? " (" + no_history + ": spatial only)"
                   : follows_motion ? " (geometry moved: its history found where it was)"
                                    : "")
        : history ? std::string("temporal: accumulation with the previous frames") +
                        (follows_motion ? " (geometry moved: its history found where it was)" : "")
                  : "temporal: " + no_history + ", this frame starts it (image unchanged)");
    plan.glossy_reason = glossy_branch_reason(scene, settings, gi && sampled, plan.glossy_branch);
    add(FrameStage::compose, true, "every frame: direct + indirect");
    add(FrameStage::tonemap, true, "every frame: the picture");
    return plan;
}

}  // namespace vplkit
