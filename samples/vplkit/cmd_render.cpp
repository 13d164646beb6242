// `vplkit render`: one frame of a scene (a standard set-up's name or a glTF file) with direct
// light, written as PNG (and linear PFM on request), with the device and per-stage GPU times.

#include "cli.hpp"
#include "commands.hpp"
#include "frame_exr.hpp"
#include "render_request.hpp"
#include "render_stats.hpp"
#include "scene_warnings.hpp"
#include "setting_flags.hpp"
#include "stats_json.hpp"
#include "vpl_view.hpp"

#include "vplkit/auto_exposure.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_setups.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/stages/flc.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

namespace vplkit::cli {

namespace {

// Fails before any rendering when a file could not be written there.
void check_output(const std::string& option, const std::filesystem::path& path,
                  std::initializer_list<std::string> extensions) {
    if (std::find(extensions.begin(), extensions.end(), path.extension().string()) == extensions.end()) {
        std::string names;
        for (const std::string& e : extensions) names += (names.empty() ? "" : " or ") + e;
        throw UsageError(option + " expects a " + names + " file name, got '" + path.string() + "'");
    }
    const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
    if (!std::filesystem::is_directory(folder)) {
        throw UsageError(option + ": the folder " + folder.string() + " does not exist");
    }
    // Found now rather than after a long render (the writers fail cleanly either way).
    if (std::filesystem::is_directory(path)) throw UsageError(option + ": " + path.string() + " is a folder");
    if (::access(folder.c_str(), W_OK) != 0) {
        throw UsageError(option + ": the folder " + folder.string() + " is not writable");
    }
}

// The whole text as a finite number, or nothing.
std::optional<float> finite_number(const std::string& text) {
    size_t used = 0;
    float value = NAN;
    try {
        value = std::stof(text, &used);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    if (used != text.size() || !std::isfinite(value)) return std::nullopt;
    return value;
}

float parse_exposure(const std::string& text) {
    const auto value = finite_number(text);
    if (!value || *value <= 0.0f) {
        throw UsageError("--exposure expects auto or a positive number (a linear scale), got '" + text + "'");
    }
    return *value;
}

float parse_fraction(const std::string& option, const std::string& text) {
    const auto value = finite_number(text);
    if (!value || *value < 0.0f || *value > 1.0f) {
        throw UsageError(option + " expects a number from 0 to 1, got '" + text + "'");
    }
    return *value;
}

// Throws "OPTION is for --method <the methods with trait>" unless the chosen method has it.
void require_method_with(const RenderSettings& settings, bool GiMethodInfo::*trait, const std::string& option) {
    if (!(gi_method(settings.method).*trait)) {
        throw UsageError(option + " is for --method " + gi_method_names(trait));
    }
}

// --flc-levels, --flc-mu, --flc-navg: only with --method flc.
void parse_flc_options(Args& args, RenderSettings& settings) {
    const auto levels = args.value("--flc-levels");
    const auto mu = args.value("--flc-mu");
    const auto navg = args.value("--flc-navg");
    const auto subtiles = args.value("--flc-subtiles");
    if ((levels || mu || navg || subtiles) && settings.method != GiMethod::flc) {
        throw UsageError("--flc-levels, --flc-mu, --flc-navg and --flc-subtiles are for --method flc");
    }
    if (subtiles) settings.flc_subtiles = parse_whole_number("--flc-subtiles", *subtiles, stages::kFlcMaxSubtiles);
    if (levels) settings.flc_levels = parse_whole_number("--flc-levels", *levels, stages::kFlcMaxLevels);
    if (mu) {
        const auto value = finite_number(*mu);
        if (!value || !(*value > 1.0f)) throw UsageError("--flc-mu expects a number above 1, got '" + *mu + "'");
        settings.flc_mu = *value;
    }
    if (navg) {
        const auto value = finite_number(*navg);
        if (!value || !(*value > 0.0f)) throw UsageError("--flc-navg expects a positive number, got '" + *navg + "'");
        settings.flc_vpls_per_point = *value;
    }
}

// Passes of one name (e.g. the importance mip levels) summed into one line, in first-seen order.
std::vector<std::pair<std::string, double>> by_stage(const std::vector<PassTiming>& timings) {
    std::vector<std::pair<std::string, double>> stages;
    std::map<std::string, size_t> index;
    std::map<std::string, int> passes;
    for (const PassTiming& t : timings) {
        auto [it, added] = index.try_emplace(t.name, stages.size());
        if (added) stages.push_back({t.name, 0.0});
        stages[it->second].second += t.gpu_ms;
        ++passes[t.name];
    }
    for (auto& [name, ms] : stages) {
        if (passes[name] > 1) name += " (" + std::to_string(passes[name]) + " passes)";
    }
    return stages;
}

// Each stage's median over frames (the stages of the first frame, in its order).
std::vector<std::pair<std::string, double>> median_stages(
    const std::vector<std::vector<std::pair<std::string, double>>>& frames) {
    std::vector<std::pair<std::string, double>> out;
    for (const auto& [name, ms] : frames.front()) {
        std::vector<double> values;
        for (const auto& frame : frames) {
            for (const auto& [n, v] : frame) {
                if (n == name) values.push_back(v);
            }
        }
        std::sort(values.begin(), values.end());
        const size_t n = values.size();
        out.push_back({name, n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2])});
    }
    return out;
}

// --smc-* options (need --vpl-source smc).
void parse_smc_options(Args& args, RenderSettings& settings, bool& given) {
    const bool smc = settings.vpl_source == VplSource::smc;
    auto take = [&](const char* option, uint64_t max, uint32_t& into, bool zero_ok = false) {
        if (auto text = args.value(option)) {
            if (!smc) throw UsageError(std::string(option) + " needs --vpl-source smc");
            into = zero_ok ? parse_index(option, *text, max) : parse_whole_number(option, *text, max);
            given = true;
        }
    };
    take("--smc-max-moves", 1u << 20, settings.smc.max_moves);
    take("--smc-resample", 1024, settings.smc.resample_ratio);
    take("--smc-radiosity-samples", 4096, settings.smc.radiosity_samples);
    take("--smc-warmup", 100000, settings.smc_warmup, true);
}

}  // namespace

RenderRequest parse_render_request(Args& args) {
    ContextOptions context_options;
    if (auto device = args.value("--device")) context_options.device = *device;
    context_options.validation = args.flag("--validation");
    const bool strict = args.flag("--strict");
    const std::string scene_arg = args.value("--scene").value_or("");
    std::optional<uint32_t> width, height, camera;
    if (auto text = args.value("--width")) width = parse_whole_number("--width", *text, 16384);
    if (auto text = args.value("--height")) height = parse_whole_number("--height", *text, 16384);
    if (auto text = args.value("--camera")) camera = parse_index("--camera", *text, 1u << 20);
    std::optional<double> time;
    if (auto text = args.value("--time")) {
        const auto value = finite_number(*text);
        if (!value) throw UsageError("--time expects a finite number of seconds, got '" + *text + "'");
        time = *value;
    }
    const std::optional<std::string> animation = args.value("--animation");
    if (animation && !time) throw UsageError("--animation needs --time T (the moment to pose it at)");
    const CameraFlags camera_flags = parse_camera_flags(args);
    std::vector<scene::Light> extra_lights;
    // A malformed light is a command-line mistake: usage, exit 2.
    try {
        while (auto spec = args.value("--sun")) extra_lights.push_back(scene::parse_sun(*spec));
        while (auto spec = args.value("--point")) extra_lights.push_back(scene::parse_point(*spec));
    } catch (const Error& e) {
        throw UsageError(e.what());
    }
    RenderSettings settings;
    // The tonemapped image's exposure: automatic (auto_exposure.hpp) unless a scale is given.
    settings.auto_exposure = true;
    if (auto text = args.value("--exposure"); text && *text != "auto") {
        settings.auto_exposure = false;
        settings.exposure = parse_exposure(*text);
    }
    if (auto text = args.value("--seed")) settings.seed = parse_index("--seed", *text, UINT32_MAX);
    if (auto text = args.value("--direct-spp"))
        settings.direct_samples = parse_whole_number("--direct-spp", *text, 65536);
    if (auto text = args.value("--direct")) {
        bool known = false;
        for (DirectSampler d :
             {DirectSampler::automatic, DirectSampler::tree, DirectSampler::tree2, DirectSampler::flat}) {
            if (*text == direct_sampler_name(d)) {
                settings.direct_sampler = d;
                known = true;
            }
        }
        if (!known) throw UsageError("--direct expects auto, tree, tree2 or flat, got '" + *text + "'");
    }
    if (auto text = args.value("--direct-interleave"))
        settings.direct_interleave = parse_whole_number("--direct-interleave", *text, 8);
    if ((settings.direct_sampler == DirectSampler::tree || settings.direct_sampler == DirectSampler::tree2) &&
        settings.direct_samples > 64) {
        throw UsageError("--direct-spp " + std::to_string(settings.direct_samples) +
                         ": the tree samples at most 64 cut nodes per pixel");
    }
    if (auto text = args.value("--method")) {
        const GiMethodInfo* method = find_gi_method(*text);
        if (!method) throw UsageError("--method expects " + gi_method_names() + ", got '" + *text + "'");
        settings.method = method->method;
    }
    parse_flc_options(args, settings);
    if (auto text = args.value("--spp")) {
        require_method_with(settings, &GiMethodInfo::samples, "--spp");
        settings.samples_per_pixel = parse_whole_number("--spp", *text, 64);
    }
    if (auto text = args.value("--block")) {
        require_method_with(settings, &GiMethodInfo::blocks, "--block");
        settings.block_size = parse_whole_number("--block", *text, 32);
    }
    if (auto text = args.value("--interleave")) {
        require_method_with(settings, &GiMethodInfo::interleaves, "--interleave");
        settings.interleave = parse_whole_number("--interleave", *text, 32);
    }
    if (auto text = args.value("--traversal")) {
        require_method_with(settings, &GiMethodInfo::chooses_traversal, "--traversal");
        if (*text == "lightcuts") {
            settings.hybrid_traversal = stages::HybridTraversal::lightcuts;
        } else if (*text != "substitute") {
            throw UsageError("--traversal expects substitute or lightcuts, got '" + *text + "'");
        }
    }
    if (auto text = args.value("--glossy-lobe")) {
        require_method_with(settings, &GiMethodInfo::samples, "--glossy-lobe");
        if (*text == "on")
            settings.glossy_branch = GlossyBranch::on;
        else if (*text == "off")
            settings.glossy_branch = GlossyBranch::off;
        else if (*text != "auto")
            throw UsageError("--glossy-lobe expects auto, on or off, got '" + *text + "'");
    }
    if (auto text = args.value("--nu-min")) {
        require_method_with(settings, &GiMethodInfo::reads_sst, "--nu-min");
        const auto value = finite_number(*text);
        if (!value) throw UsageError("--nu-min expects a number, got '" + *text + "'");
        settings.sst.nu_min = *value;
    }
    if (auto text = args.value("--sigma-max")) {
        require_method_with(settings, &GiMethodInfo::reads_sst, "--sigma-max");
        const auto value = finite_number(*text);
        if (!value || *value < 0.0f) throw UsageError("--sigma-max expects a number >= 0, got '" + *text + "'");
        settings.sst.sigma_max = *value;
        settings.sigma_max_scene_fraction.reset();  // absolute, as given
    }
    if (auto text = args.value("--gi-resolution")) {
        if (settings.method == GiMethod::none) throw UsageError("--gi-resolution needs an indirect-light --method");
        if (*text == "half")
            settings.half_resolution_gi = true;
        else if (*text != "full")
            throw UsageError("--gi-resolution expects full or half, got '" + *text + "'");
    }
    bool denoise_given = false;
    if (auto text = args.value("--denoise")) {
        denoise_given = true;
        if (*text == "temporal")
            settings.denoise = DenoiseMode::temporal;
        else if (*text == "svgf")
            settings.denoise = DenoiseMode::svgf;
        else if (*text != "off")
            throw UsageError("--denoise expects off, temporal or svgf, got '" + *text + "'");
        if (settings.denoise != DenoiseMode::off && settings.method == GiMethod::none) {
            throw UsageError("--denoise filters indirect light: give an indirect-light --method");
        }
    }
    if (auto text = args.value("--firefly-sigma")) {
        if (settings.denoise == DenoiseMode::off) throw UsageError("--firefly-sigma needs --denoise temporal or svgf");
        const auto value = finite_number(*text);
        if (!value || *value < 0.0f) throw UsageError("--firefly-sigma expects a number >= 0, got '" + *text + "'");
        settings.denoise_options.firefly_k_sigma = *value;
    }
    bool vpl_options_given = false;
    if (auto text = args.value("--vpl-source")) {
        vpl_options_given = true;
        if (*text == "ir")
            settings.vpl_source = VplSource::ir;
        else if (*text == "brsm")
            settings.vpl_source = VplSource::brsm;
        else if (*text == "smc")
            settings.vpl_source = VplSource::smc;
        else if (*text == "auto")
            settings.vpl_source = VplSource::automatic;
        else
            throw UsageError("--vpl-source expects ir, brsm, smc or auto, got '" + *text + "'");
    }
    const bool brsm = settings.vpl_source == VplSource::brsm;
    const bool smc = settings.vpl_source == VplSource::smc;
    if (auto text = args.value("--vpls")) {
        vpl_options_given = true;
        settings.vpl_paths = parse_whole_number("--vpls", *text, 1u << 24);
        settings.brsm.vpl_count = settings.vpl_paths;
        if (smc) settings.smc.budget = parse_whole_number("--vpls", *text, stages::kSmcMaxBudget);
    }
    if (auto text = args.value("--bounces")) {
        vpl_options_given = true;
        if (brsm) throw UsageError("--bounces is for --vpl-source ir: BRSM VPLs are the first bounce only");
        settings.vpl_bounces = parse_whole_number("--bounces", *text, 16);
        settings.smc.bounces = settings.vpl_bounces;
    }
    parse_smc_options(args, settings, vpl_options_given);
    const auto rsm_resolution = args.value("--rsm-resolution");
    const auto brsm_samples = args.value("--brsm-samples");
    const auto brsm_defensive = args.value("--brsm-defensive");
    vpl_options_given = vpl_options_given || rsm_resolution || brsm_samples || brsm_defensive;
    if ((rsm_resolution || brsm_samples || brsm_defensive) && !brsm) {
        throw UsageError("--rsm-resolution, --brsm-samples and --brsm-defensive need --vpl-source brsm");
    }
    if (rsm_resolution) settings.rsm_resolution = parse_whole_number("--rsm-resolution", *rsm_resolution, 2048);
    if (brsm_samples) settings.brsm.samples_per_texel = parse_whole_number("--brsm-samples", *brsm_samples, 1024);
    if (brsm_defensive) settings.brsm.defensive_fraction = parse_fraction("--brsm-defensive", *brsm_defensive);
    settings.vpls_only = args.flag("--vpls-only");
    bool lambertian = false;
    if (auto text = args.value("--brdf")) {
        if (*text != "gltf" && *text != "lambert")
            throw UsageError("--brdf expects gltf or lambert, got '" + *text + "'");
        lambertian = *text == "lambert";
    }
    if (auto text = args.value("--exact-clamp")) {
        if (!gi_method(settings.method).ground_truth) {
            throw UsageError("--exact-clamp needs --method " + gi_method_names(&GiMethodInfo::ground_truth));
        }
        settings.exact_min_distance_fraction = parse_fraction("--exact-clamp", *text);
    }
    settings.force_all_stages = args.flag("--all-stages");
    settings.reuse_static_work = !args.flag("--no-reuse");
    if (vpl_options_given && settings.method == GiMethod::none && !settings.vpls_only) {
        throw UsageError(
            "--vpl-source, --vpls, --bounces and the --brsm options need an indirect-light --method "
            "or --vpls-only (direct light uses no VPLs)");
    }
    RenderRequest r;
    r.context = context_options;
    r.strict = strict;
    r.scene_arg = scene_arg;
    r.width = width;
    r.height = height;
    r.camera = camera;
    r.time = time;
    r.animation = animation;
    r.camera_flags = camera_flags;
    r.extra_lights = std::move(extra_lights);
    r.settings = settings;
    r.lambertian = lambertian;
    r.denoise_given = denoise_given;
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
    const bool is_file =
        scene_arg.find('/') != std::string::npos || scene_arg.ends_with(".gltf") || scene_arg.ends_with(".glb");
    if (is_file) {
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
    scene.lights.insert(scene.lights.end(), request.extra_lights.begin(), request.extra_lights.end());
    loaded.target = apply_camera_flags(request.camera_flags, scene, loaded.target);
    report_scene_warnings(scene, request.strict);
    if (request.lambertian) scene::use_lambertian_materials(scene);
    loaded.load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start).count();
    return loaded;
}

namespace {

int render_or_plan(Args& args, bool plan_only) {
    RenderRequest request = parse_render_request(args);
    RenderSettings& settings = request.settings;
    const ContextOptions& context_options = request.context;
    const GiMethodInfo& method = gi_method(settings.method);
    const std::filesystem::path out = args.value("--out").value_or("vplkit.png");
    const auto out_hdr = args.value("--out-hdr");
    const auto out_direct = args.value("--out-direct");
    const auto out_indirect = args.value("--out-indirect");
    uint32_t frames = 1;
    if (auto text = args.value("--frames")) frames = parse_whole_number("--frames", *text, 1000);
    // Several frames on the static camera: jittered and averaged (antialias.hpp) unless asked not to.
    settings.antialias = !args.flag("--no-antialias") && frames > 1 && !settings.vpls_only;
    const auto stats_path = plan_only ? std::nullopt : args.value("--stats");
    if (settings.vpls_only && (out_hdr || out_direct || out_indirect)) {
        throw UsageError(
            "--vpls-only writes only --out (the VPL view); drop --out-hdr, --out-direct and --out-indirect");
    }
    args.finish();
    validate_render_request(request);
    check_output("--out", out, {".png", ".exr"});
    if (out_hdr) check_output("--out-hdr", *out_hdr, {".pfm", ".exr"});
    if (out_direct) check_output("--out-direct", *out_direct, {".pfm"});
    if (out_indirect) check_output("--out-indirect", *out_indirect, {".pfm"});
    if (stats_path) check_output("--stats", *stats_path, {".json"});
    const auto is_exr = [](const std::filesystem::path& path) { return path.extension() == ".exr"; };
    if (settings.vpls_only && is_exr(out)) throw UsageError("--vpls-only draws the VPLs into a PNG: give --out a .png");
    // The EXR's albedo, normal, depth and variance layers come from the G-buffer and the denoiser.
    settings.read_back_aovs = is_exr(out) || (out_hdr && is_exr(*out_hdr));

    LoadedScene loaded = load_request_scene(request);
    const scene::Scene& scene = loaded.scene;
    const std::string& described = loaded.described;
    const double load_ms = loaded.load_ms;

    if (plan_only) {
        // No device work: the plan is a function of the scene and the settings.
        std::printf("scene: %s: %zu triangles, %zu materials, %zu lights, %zu emissive triangles\n", described.c_str(),
                    scene.triangle_count(), scene.materials.size(), scene.lights.size(),
                    scene.emissive_triangles.size());
        std::printf("method: %s, %ux%u\n", gi_method_name(settings.method), settings.width, settings.height);
        const FramePlan plan = plan_frame(scene, settings, "");
        std::printf("%s\n%s", plan.summary().c_str(), with_flags(plan.describe()).c_str());
        return 0;
    }
    auto context = Context::create(context_options);
    const DeviceInfo& device = context->info();
    std::printf("device: %s (%s): %s\n", device.name.c_str(), device.type_name.c_str(), device.reason.c_str());
    std::printf("scene: %s: %zu triangles, %zu materials, %zu lights, %zu emissive triangles (loaded in %.0f ms)\n",
                described.c_str(), scene.triangle_count(), scene.materials.size(), scene.lights.size(),
                scene.emissive_triangles.size(), load_ms);

    Renderer renderer(*context, scene);
    std::printf("bvh: %zu nodes, depth %u, built in %.0f ms\n", renderer.bvh().nodes.size(), renderer.bvh().depth,
                renderer.bvh_build_ms());
    const bool terminal = isatty(fileno(stderr));
    settings.progress = [terminal](uint32_t done, uint32_t total) {
        if (terminal) {
            std::fprintf(stderr, "\r[exact gi] %u/%u VPLs", done, total);
            if (done == total) std::fprintf(stderr, "\r%40s\r", "");
        } else if (done == total || done % 1024 < 32) {
            std::fprintf(stderr, "[exact gi] %u/%u VPLs\n", done, total);
        }
        std::fflush(stderr);
    };
    settings.smc_warmup_progress = [terminal](uint32_t done, uint32_t total) {
        if (terminal) {
            std::fprintf(stderr, "\r[smc warm-up] %u/%u updates", done, total);
            if (done == total) std::fprintf(stderr, "\r%40s\r", "");
        } else if (done == total || done % 10 == 0) {
            std::fprintf(stderr, "[smc warm-up] %u/%u updates\n", done, total);
        }
        std::fflush(stderr);
    };
    // Several frames: the first pays for lavapipe's shader compiles at first dispatch (and a
    // GPU's warm-up); the times printed are each stage's median over the frames after it.
    std::vector<std::vector<std::pair<std::string, double>>> frame_stages;
    std::vector<std::vector<PassTiming>> frame_timings;  // for --stats
    PlanLog plans;
    RenderedImage image;
    for (uint32_t frame = 0; frame < frames; ++frame) {
        if (frames > 1) std::fprintf(stderr, "[render] frame %u/%u\n", frame + 1, frames);
        // Accumulating: every frame draws new samples (the frame counter) over the same VPLs, and
        // with anti-aliasing its G-buffer moves by its sub-pixel offset.
        if (settings.denoise != DenoiseMode::off || settings.antialias) settings.frame = frame;
        image = renderer.render(scene.camera(), settings);
        if (frame > 0 || frames == 1) frame_stages.push_back(by_stage(image.timings));
        frame_timings.push_back(image.timings);
        plans.add(frame, image.plan);
    }
    std::printf("%s\n", image.plan_summary.c_str());
    for (const std::string& note : image.notes) std::printf("note: %s\n", with_flags(note).c_str());
    const bool made_vpls = settings.method != GiMethod::none || settings.vpls_only;
    if (settings.method == GiMethod::flc && !settings.vpls_only) {
        std::printf("indirect: %u flc VPLs (%u levels, mu %g, N_avg %g), splatted unshadowed\n", image.vpl_count,
                    settings.flc_levels, settings.flc_mu, settings.flc_vpls_per_point);
    } else if (made_vpls && image.vpl_source == VplSource::brsm) {
        std::printf(
            "%s: %u VPLs by BRSM from %zu lights' %u^2 shadow maps (%u samples per texel, defensive share %.2f)\n",
            settings.vpls_only ? "vpls" : "indirect", image.vpl_count, scene.lights.size(), settings.rsm_resolution,
            settings.brsm.samples_per_texel, settings.brsm.defensive_fraction);
    } else if (made_vpls && image.vpl_source == VplSource::smc && image.smc) {
        const stages::SmcCounts& c = *image.smc;
        std::printf(
            "%s: %u VPLs by SMC (budget %u, %u bounces); this frame: %u invalid (%u revalidated), %u candidates, "
            "M_strong %u, M_min %u, %u removed, %u moved in\n",
            settings.vpls_only ? "vpls" : "indirect", image.vpl_count, settings.smc.budget, settings.smc.bounces,
            c.invalid, c.revalidated, c.candidates, c.strong, c.min_moves, c.removed, c.moved);
    } else if (made_vpls) {
        std::printf("%s: %u VPLs from %u light paths x %u bounces\n", settings.vpls_only ? "vpls" : "indirect",
                    image.vpl_count, settings.vpl_paths, settings.vpl_bounces);
    }
    if (method.ground_truth && image.dropped_pixels > 0) {
        std::printf("warning: %u pixels had a non-finite VPL contribution left out\n", image.dropped_pixels);
    }
    if (method.samples && !settings.vpls_only && image.vpl_count > 0) {
        const stages::GiCounts& c = image.gi_counts;
        std::printf("%s: %u spp", gi_method_name(settings.method), settings.samples_per_pixel);
        if (method.blocks) std::printf(", %ux%u blocks", settings.block_size, settings.block_size);
        if (settings.interleave > 1) std::printf(", %ux%u interleaved", settings.interleave, settings.interleave);
        if (settings.hybrid_traversal == stages::HybridTraversal::lightcuts) std::printf(", rtslc's traversal");
        if (method.reads_sst) std::printf(", nu_min %.2f, sigma_max %.3g", settings.sst.nu_min, image.sst_sigma_max);
        std::printf("; %.2f tree levels per traversal (%u traversals), %u dead branches", c.levels_per_traversal(),
                    c.traversals, c.dead_branches);
        if (method.mock_cuts) std::printf(", %u mock-cut pixels", c.mock_cut_pixels);
        std::printf("\n");
    }
    if (settings.half_resolution_gi && !settings.vpls_only) {
        std::printf("gi at %ux%u, upsampled: %u pixels took the nearest sample (no similar one), %u got none\n",
                    image.gi_width, image.gi_height, image.upsample_counts.fallback_pixels,
                    image.upsample_counts.empty_pixels);
    }
    if (settings.denoise != DenoiseMode::off && !settings.vpls_only && !method.ground_truth) {
        std::printf(
            "denoise %s over %u frame(s); firefly clamp (mean + %.1f sigma) moved %.4f%% of the accumulated "
            "indirect irradiance's luminance onto the outliers' neighbours in the last (none removed)\n",
            denoise_mode_name(settings.denoise), frames, settings.denoise_options.firefly_k_sigma,
            100.0 * image.firefly_moved_fraction);
    }
    if (image.non_finite_pixels > 0) {
        throw Error("render: " + std::to_string(image.non_finite_pixels) +
                    " pixels came out NaN or infinite; no image written (this is a bug: please report it)");
    }

    if (frames > 1) {
        std::printf("%ux%u, GPU time per stage (median of frames 2..%u):\n", image.width, image.height, frames);
    } else {
        std::printf("%ux%u, GPU time per stage:\n", image.width, image.height);
    }
    double total = 0.0;
    for (const auto& [name, ms] : median_stages(frame_stages)) {
        std::printf("  %-30s %9.3f ms\n", name.c_str(), ms);
        total += ms;
    }
    std::printf("  %-30s %9.3f ms\n", "total", total);
    if (method.ground_truth && !settings.vpls_only) {
        std::printf("exact gi by the host's wall clock: %.3f ms\n", image.exact_gi_wall_ms);
    }

    std::vector<std::string> written;
    const auto wrote = [&written](const std::filesystem::path& path) {
        std::printf("wrote %s\n", path.string().c_str());
        written.push_back(path.string());
    };
    const auto write_stats = [&] {
        if (!stats_path) return;
        nlohmann::ordered_json stats = stats_header("render");
        stats["device"] = device_stats(device);
        stats["scene"] = {{"name", described},
                          {"triangles", scene.triangle_count()},
                          {"materials", scene.materials.size()},
                          {"lights", scene.lights.size()},
                          {"emissive_triangles", scene.emissive_triangles.size()},
                          {"load_ms", json_number(load_ms)},
                          {"bvh_build_ms", json_number(renderer.bvh_build_ms())}};
        stats["settings"] = {{"method", gi_method_name(settings.method)},
                             {"denoise", denoise_mode_name(settings.denoise)},
                             {"exposure", json_number(image.exposure)},
                             {"seed", settings.seed}};
        stats["width"] = image.width;
        stats["height"] = image.height;
        stats["frames"] = frames;
        stats["plans"] = plans.json();
        stats.update(timing_stats(frame_timings));
        stats["counters"] = counters_stats(image, settings);
        // Null when the denoiser did not run (no firefly clamp).
        stats["firefly_moved_fraction"] =
            image.plan.runs(FrameStage::denoise) ? json_number(image.firefly_moved_fraction) : nullptr;
        stats["outputs"] = written;
        write_json_file(*stats_path, stats);
        std::printf("wrote %s\n", stats_path->c_str());
    };
    if (settings.antialias) {
        std::printf("anti-aliasing: the mean of %u frames, each G-buffer at a Halton(2,3) sub-pixel offset%s\n", frames,
                    settings.denoise != DenoiseMode::off && !method.ground_truth
                        ? " (the indirect light: the filter's own accumulation)"
                        : "");
    }
    if (!settings.vpls_only && settings.auto_exposure) {
        std::printf(
            "exposure %.3g (automatic: the lit pixels' %.0fth luminance percentile to %.1f before the tone "
            "curve; --exposure E fixes it; HDR outputs are not scaled)\n",
            image.exposure, 100.0 * kAutoExposurePercentile, kAutoExposureTarget);
    } else if (!settings.vpls_only) {
        std::printf("exposure %.3g (--exposure)\n", image.exposure);
    }
    if (settings.vpls_only) {
        if (image.vpl_count == 0) {
            throw Error("render: no VPLs were placed (no light reaches a reflecting surface); no image written");
        }
        const stages::CameraView view = stages::camera_view(scene.camera(), image.width, image.height);
        const VplView drawn = draw_vpl_view(image, view.view_projection, view.position);
        std::printf("vpl view: %u VPLs seen by the camera, %u hidden behind nearer surfaces, %u off screen\n",
                    drawn.visible, drawn.hidden, drawn.off_screen);
        write_png(out, image.width, image.height, drawn.rgba8);
        wrote(out);
        write_stats();
        return 0;
    }
    if (is_exr(out)) {
        write_frame_exr(out, image, settings);
    } else {
        write_png(out, image.width, image.height, image.rgba8);
    }
    wrote(out);
    if (out_hdr && is_exr(*out_hdr)) {
        write_frame_exr(*out_hdr, image, settings);
        wrote(*out_hdr);
    } else if (out_hdr) {
        write_pfm(*out_hdr, image.width, image.height, image.radiance);
        wrote(*out_hdr);
    }
    if (out_direct) {
        write_pfm(*out_direct, image.width, image.height, image.direct);
        wrote(*out_direct);
    }
    if (out_indirect) {
        write_pfm(*out_indirect, image.width, image.height, image.indirect);
        wrote(*out_indirect);
    }
    write_stats();
    return 0;
}

}  // namespace

int run_render(Args& args) {
    return render_or_plan(args, false);
}
int run_plan(Args& args) {
    return render_or_plan(args, true);
}

}  // namespace vplkit::cli
