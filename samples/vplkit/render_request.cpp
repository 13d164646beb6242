// What render's options say together (RenderOptions::request: an option for another method, a VPL
// option without VPLs), the sampling options checked before any work, and the scene a request
// names, loaded (a set-up or a file, the extra lights, the camera flags).

#include "render_request.hpp"
#include "scene_warnings.hpp"

#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/scene_setups.hpp"
#include "vplkit/stages/smc.hpp"

#include <chrono>
#include <cstdlib>
#include <optional>
#include <string>

namespace vplkit::cli {

void filter_frames_by_default(RenderRequest& request) {
    const GiMethodInfo& method = gi_method(request.settings.method);
    if (!request.denoise_given && method.vpls != GiVpls::none && !method.ground_truth) {
        request.settings.denoise = DenoiseMode::svgf;
    }
}

namespace {

// Throws "OPTION is for --method <the methods with trait>" unless the chosen method has it.
void require_method_with(const RenderSettings& settings, bool GiMethodInfo::*trait, const std::string& option) {
    if (!(gi_method(settings.method).*trait)) {
        throw UsageError(option + " is for --method " + gi_method_names(trait));
    }
}

}  // namespace

bool RenderOptions::given(const std::string& option) const {
    return command_.count(option) > 0;
}

RenderRequest RenderOptions::request() const {
    RenderRequest r = request_;
    RenderSettings& settings = r.settings;
    if (r.animation && !r.time) throw UsageError("--animation needs --time T (the moment to pose it at)");
    check_camera_flags(r.camera_flags);
    for (const std::string& spec : suns_) r.extra_lights.push_back(scene::parse_sun(spec));
    for (const std::string& spec : points_) r.extra_lights.push_back(scene::parse_point(spec));
    // The tonemapped image's exposure: automatic (auto_exposure.hpp) unless a scale is given.
    settings.auto_exposure = exposure_ == "auto";
    if (!settings.auto_exposure) settings.exposure = std::strtof(exposure_.c_str(), nullptr);
    for (DirectSampler d : {DirectSampler::automatic, DirectSampler::tree, DirectSampler::tree2, DirectSampler::flat}) {
        if (direct_ == direct_sampler_name(d)) settings.direct_sampler = d;
    }
    if ((settings.direct_sampler == DirectSampler::tree || settings.direct_sampler == DirectSampler::tree2) &&
        settings.direct_samples > 64) {
        throw UsageError("--direct-spp " + std::to_string(settings.direct_samples) +
                         ": the tree samples at most 64 cut nodes per pixel");
    }
    settings.method = find_gi_method(method_)->method;
    // --budget-ms (render, sequence, view) chooses the method: its knobs may come without one.
    const CLI::Option* budget_option = command_.get_option_no_throw("--budget-ms");
    const bool budget = budget_option && budget_option->count() > 0;
    if ((given("--flc-levels") || given("--flc-mu") || given("--flc-navg") || given("--flc-subtiles")) &&
        settings.method != GiMethod::flc) {
        throw UsageError("--flc-levels, --flc-mu, --flc-navg and --flc-subtiles are for --method flc");
    }
    if (given("--spp") && !budget) require_method_with(settings, &GiMethodInfo::samples, "--spp");
    if (given("--block") && !budget) require_method_with(settings, &GiMethodInfo::blocks, "--block");
    if (given("--interleave")) require_method_with(settings, &GiMethodInfo::interleaves, "--interleave");
    if (given("--traversal")) require_method_with(settings, &GiMethodInfo::chooses_traversal, "--traversal");
    if (traversal_ == "lightcuts") settings.hybrid_traversal = stages::HybridTraversal::lightcuts;
    if (given("--glossy-lobe")) require_method_with(settings, &GiMethodInfo::samples, "--glossy-lobe");
    settings.glossy_branch = glossy_lobe_ == "on"    ? GlossyBranch::on
                             : glossy_lobe_ == "off" ? GlossyBranch::off
                                                     : GlossyBranch::automatic;
    if (given("--nu-min")) require_method_with(settings, &GiMethodInfo::reads_sst, "--nu-min");
    if (given("--sigma-max")) {
        require_method_with(settings, &GiMethodInfo::reads_sst, "--sigma-max");
        settings.sigma_max_scene_fraction.reset();  // absolute, as given
    }
    if (given("--gi-resolution") && settings.method == GiMethod::none && !budget) {
        throw UsageError("--gi-resolution needs an indirect-light --method");
    }
    settings.half_resolution_gi = gi_resolution_ == "half";
    r.denoise_given = given("--denoise");
    settings.denoise = denoise_ == "temporal" ? DenoiseMode::temporal
                       : denoise_ == "svgf"   ? DenoiseMode::svgf
                                              : DenoiseMode::off;
    if (settings.denoise != DenoiseMode::off && settings.method == GiMethod::none && !budget) {
        throw UsageError("--denoise filters indirect light: give an indirect-light --method");
    }
    if (given("--firefly-sigma") && settings.denoise == DenoiseMode::off) {
        throw UsageError("--firefly-sigma needs --denoise temporal or svgf");
    }
    settings.vpl_source = vpl_source_ == "ir"     ? VplSource::ir
                          : vpl_source_ == "brsm" ? VplSource::brsm
                          : vpl_source_ == "smc"  ? VplSource::smc
                                                  : VplSource::automatic;
    const bool brsm = settings.vpl_source == VplSource::brsm;
    const bool smc = settings.vpl_source == VplSource::smc;
    settings.brsm.vpl_count = settings.vpl_paths;
    if (smc && given("--vpls")) {
        if (settings.vpl_paths > stages::kSmcMaxBudget) {
            throw UsageError("--vpls expects a whole number from 1 to " + std::to_string(stages::kSmcMaxBudget) +
                             " with --vpl-source smc, got '" + std::to_string(settings.vpl_paths) + "'");
        }
        settings.smc.budget = settings.vpl_paths;
    }
    if (given("--bounces")) {
        if (brsm) throw UsageError("--bounces is for --vpl-source ir: BRSM VPLs are the first bounce only");
        settings.smc.bounces = settings.vpl_bounces;
    }
    for (const char* option : {"--smc-max-moves", "--smc-resample", "--smc-radiosity-samples", "--smc-warmup"}) {
        if (given(option) && !smc) throw UsageError(std::string(option) + " needs --vpl-source smc");
    }
    const bool brsm_options = given("--rsm-resolution") || given("--brsm-samples") || given("--brsm-defensive");
    if (brsm_options && !brsm) {
        throw UsageError("--rsm-resolution, --brsm-samples and --brsm-defensive need --vpl-source brsm");
    }
    r.lambertian = brdf_ == "lambert";
    if (given("--exact-clamp") && !gi_method(settings.method).ground_truth) {
        throw UsageError("--exact-clamp needs --method " + gi_method_names(&GiMethodInfo::ground_truth));
    }
    settings.reuse_static_work = !no_reuse_;
    const bool vpl_options = given("--vpl-source") || given("--vpls") || given("--bounces") || brsm_options ||
                             given("--smc-max-moves") || given("--smc-resample") || given("--smc-radiosity-samples") ||
                             given("--smc-warmup");
    if (vpl_options && settings.method == GiMethod::none && !settings.vpls_only && !budget) {
        throw UsageError(
            "--vpl-source, --vpls, --bounces and the --brsm options need an indirect-light --method "
            "or --vpls-only (direct light uses no VPLs)");
    }
    return r;
}

void validate_render_request(const RenderRequest& request) {
    // A sampling option the method refuses (e.g. an interleave that does not divide the block)
    // is a command-line mistake, found before any work.
    try {
        validate_gi_settings(request.settings);
    } catch (const Error& e) {
        throw UsageError(e.what());
    }
}

namespace {

bool is_scene_file(const std::string& scene_arg) {
    return scene_arg.find('/') != std::string::npos || scene_arg.ends_with(".gltf") || scene_arg.ends_with(".glb");
}

// What every loaded scene gets: the extra lights, the camera flags, the warnings, the BRDF.
void finish_loaded_scene(const RenderRequest& request, LoadedScene& loaded) {
    scene::Scene& scene = loaded.active();
    scene.lights.insert(scene.lights.end(), request.extra_lights.begin(), request.extra_lights.end());
    loaded.target = apply_camera_flags(request.camera_flags, scene, loaded.target);
    report_scene_warnings(scene, request.strict);
    if (request.lambertian) scene::use_lambertian_materials(scene);
}

}  // namespace

LoadedScene load_request_scene(RenderRequest& request) {
    const std::optional<uint32_t>& camera = request.camera;
    const std::string& scene_arg = request.scene_arg;
    const std::optional<uint32_t>& width = request.width;
    const std::optional<uint32_t>& height = request.height;
    RenderSettings& settings = request.settings;
    LoadedScene loaded;
    scene::Scene& scene = loaded.scene;
    std::string& described = loaded.described;
    // The scene: a set-up name, or a file.
    const auto load_start = std::chrono::steady_clock::now();
    scene::LoadOptions load_options;
    load_options.camera = camera;
    load_options.time = request.time;
    load_options.animation = request.animation;
    if (is_scene_file(scene_arg)) {
        scene = scene::load_gltf(scene_arg, load_options);
        described = scene_arg;
        loaded.target = scene.bounds.center();
        settings.width = width.value_or(640);
        settings.height = height.value_or(360);
    } else {
        const scene::Setups setups = scene::load_setups(VPLKIT_SETUPS_FILE);
        const scene::Setup& setup = scene_arg.empty() ? setups.default_setup() : setups.find(scene_arg);
        scene = scene::load_setup_scene(setup, load_options);
        described = setup.name + " (" + setup.scene.string() + ")";
        loaded.target = setup.camera.target;
        settings.width = width.value_or(setup.width ? setup.width : 640);
        settings.height = height.value_or(setup.height ? setup.height : 360);
    }
    finish_loaded_scene(request, loaded);
    loaded.load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start).count();
    return loaded;
}

LoadedScene load_request_posable(RenderRequest& request) {
    const std::string& scene_arg = request.scene_arg;
    const auto load_start = std::chrono::steady_clock::now();
    LoadedScene loaded;
    scene::LoadOptions load_options;
    load_options.camera = request.camera;
    load_options.time = request.time.value_or(0.0);
    load_options.animation = request.animation;
    if (is_scene_file(scene_arg)) {
        loaded.posable = std::make_unique<scene::PosableScene>(scene_arg, load_options);
        loaded.described = scene_arg;
        loaded.target = loaded.active().bounds.center();
        request.settings.width = request.width.value_or(640);
        request.settings.height = request.height.value_or(360);
    } else {
        // A set-up's file posed; its lights and camera added as load_setup_scene adds them (a pose
        // keeps what the caller added).
        const scene::Setups setups = scene::load_setups(VPLKIT_SETUPS_FILE);
        const scene::Setup& setup = scene_arg.empty() ? setups.default_setup() : setups.find(scene_arg);
        loaded.posable = std::make_unique<scene::PosableScene>(scene::require_scene(setup), load_options);
        scene::Scene& scene = loaded.active();
        if (scene.animations.empty()) {
            throw UsageError("--animate poses a glTF file's animations: set-up '" + setup.name + "' (" +
                             setup.scene_as_written + ") has none");
        }
        scene.lights.insert(scene.lights.end(), setup.lights.begin(), setup.lights.end());
        if (!request.camera) {
            if (scene.cameras.size() == 1 && scene.cameras[0].origin == scene::CameraOrigin::generated) {
                scene.cameras.clear();
            }
            scene.cameras.push_back(scene::setup_camera(setup, scene.bounds));
            scene.active_camera = uint32_t(scene.cameras.size() - 1);
        }
        loaded.described = setup.name + " (" + setup.scene.string() + ")";
        loaded.target = setup.camera.target;
        request.settings.width = request.width.value_or(setup.width ? setup.width : 640);
        request.settings.height = request.height.value_or(setup.height ? setup.height : 360);
    }
    finish_loaded_scene(request, loaded);
    loaded.load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start).count();
    return loaded;
}

}  // namespace vplkit::cli
