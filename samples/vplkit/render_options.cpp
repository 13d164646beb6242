// Render's options, declared once: the name, the help, the check (what they say together is
// checked after parsing: RenderOptions::request, render_request.cpp).

#include "cli_app.hpp"
#include "cli_checks.hpp"
#include "device_options.hpp"
#include "render_request.hpp"

#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/stages/flc.hpp"
#include "vplkit/stages/smc.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace vplkit::cli {

namespace {

const char* const kSceneGroup = "scene and camera";
const char* const kMethodGroup = "indirect light: the method and its knobs";
const char* const kVplGroup = "indirect light: the VPLs";
const char* const kDirectGroup = "direct light";
const char* const kFilterGroup = "the image";

// "direct (default): direct light only; or indirect light from VPLs by\nexact: ...;\nsst: ..."
std::string method_help() {
    std::string text;
    for (const GiMethodInfo& m : gi_methods()) {
        if (m.vpls == GiVpls::none) {
            text += std::string(m.name) + ": " + std::string(m.summary) + "; or indirect light from VPLs by";
        } else {
            text += "\n" + std::string(m.name) + ": " + std::string(m.summary) + ";";
        }
    }
    if (!text.empty() && text.back() == ';') text.pop_back();
    return text;
}

std::vector<std::string> method_names() {
    std::vector<std::string> names;
    for (const GiMethodInfo& m : gi_methods()) names.emplace_back(m.name);
    return names;
}

// --sun and --point: the scene loader's own parse, as a check (its message names the light).
CLI::Validator light_check(scene::Light (*parse)(std::string_view)) {
    return CLI::Validator(
        [parse](std::string& text) -> std::string {
            try {
                parse(text);
                return "";
            } catch (const Error& e) {
                return e.what();
            }
        },
        "", "light");
}

}  // namespace

void add_light_options(CLI::App& command, std::vector<std::string>& suns, std::vector<std::string>& points) {
    command.add_option("--sun", suns, "add a directional light travelling along (DX,DY,DZ), colour RGB, I lux")
        ->option_text("DX,DY,DZ,R,G,B,I (repeatable)")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check(light_check(scene::parse_sun));
    command.add_option("--point", points, "add a point light at (X,Y,Z), colour RGB, I candela")
        ->option_text("X,Y,Z,R,G,B,I (repeatable)")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check(light_check(scene::parse_point));
}

RenderOptions::RenderOptions(CLI::App& command) : command_(command) {
    RenderSettings& s = request_.settings;
    add_device_options(command, request_.context);
    command.add_flag("--strict", request_.strict,
                     "fail (exit 1, nothing written) when the scene has a warning: a feature of the file that vplkit "
                     "skips or approximates (printed as 'warning: ...')");

    command
        .add_option("--scene", request_.scene_arg,
                    "a standard set-up from scenes/setups.txt (default: its default, 'cornell'), or a .gltf/.glb "
                    "file (its own camera, or one framing the scene)")
        ->option_text("NAME|FILE")
        ->group(kSceneGroup);
    whole_number(
        command.add_option_function<uint32_t>(
            "--width", [this](uint32_t v) { request_.width = v; }, "image width (default: the set-up's, else 640)"),
        "W", 1, 16384)
        ->group(kSceneGroup);
    whole_number(
        command.add_option_function<uint32_t>(
            "--height", [this](uint32_t v) { request_.height = v; }, "image height (default: the set-up's, else 360)"),
        "H", 1, 16384)
        ->group(kSceneGroup);
    whole_number(
        command.add_option_function<uint32_t>(
            "--camera", [this](uint32_t v) { request_.camera = v; }, "use the file's camera N instead of the set-up's"),
        "N", 0, 1u << 20)
        ->group(kSceneGroup);
    number(command.add_option_function<double>(
               "--time", [this](double v) { request_.time = v; },
               "pose the file's animations at T seconds (each channel holds its first and last keys outside them; "
               "default: the rest pose, with a warning)"),
           "T", NumberRange{-INFINITY, INFINITY, false, false, "a finite number of seconds"})
        ->group(kSceneGroup);
    command
        .add_option_function<std::string>(
            "--animation", [this](const std::string& v) { request_.animation = v; },
            "with --time: only animation A (its name or index; default: all of them)")
        ->option_text("A")
        ->group(kSceneGroup);
    add_camera_options(command, request_.camera_flags);
    for (const char* name : {"--position", "--target", "--up", "--fov"}) command.get_option(name)->group(kSceneGroup);
    add_light_options(command, suns_, points_);
    command.get_option("--sun")->group(kSceneGroup);
    command.get_option("--point")->group(kSceneGroup);
    one_of(command
               .add_option("--brdf", brdf_,
                           "gltf: the file's metallic-roughness materials; lambert: every material a pure "
                           "Lambertian of its base colour (for diffuse-only references)")
               ->capture_default_str(),
           {"gltf", "lambert"})
        ->group(kSceneGroup);

    one_of(command.add_option("--method", method_, method_help())->capture_default_str(), method_names())
        ->group(kMethodGroup);
    whole_number(command
                     .add_option("--spp", s.samples_per_pixel,
                                 "sst: traversals per pixel; rtslc, hybrid: the cut size, one traversal per cut "
                                 "node; each is one shadow ray")
                     ->capture_default_str(),
                 "N", 1, 64)
        ->group(kMethodGroup);
    whole_number(command.add_option("--block", s.block_size, "rtslc, hybrid: pixels share a cut per K x K block")
                     ->capture_default_str(),
                 "K", 1, 32)
        ->group(kMethodGroup);
    whole_number(
        command.add_option("--interleave", s.interleave, "rtslc: interleaved sampling over M x M sub-blocks (1: off)")
            ->capture_default_str(),
        "M", 1, 32)
        ->group(kMethodGroup);
    one_of(command
               .add_option("--traversal", traversal_,
                           "hybrid: below each cut node, substitute (the thesis' early-stop traversal) or "
                           "lightcuts (rtslc's traversal to a leaf over hybrid's cuts)")
               ->capture_default_str(),
           {"substitute", "lightcuts"})
        ->group(kMethodGroup);
    one_of(command
               .add_option("--glossy-lobe", glossy_lobe_,
                           "sst, rtslc, hybrid: the glossy branch (receivers smoother than roughness 0.5 sample "
                           "the diffuse or the glossy lobe per sample, glossy to a leaf VPL); auto: on when a "
                           "material of the scene can be that smooth (`vplkit plan` names them), else compiled out")
               ->capture_default_str(),
           {"auto", "on", "off"})
        ->group(kMethodGroup);
    one_of(command
               .add_option("--gi-resolution", gi_resolution_,
                           "full, or half: indirect light at half resolution, joint bilateral upsampling to full")
               ->capture_default_str(),
           {"full", "half"})
        ->group(kMethodGroup);
    number(command
               .add_option("--nu-min", s.sst.nu_min,
                           "sst, hybrid: a tree node is sampled as a whole when its normal similarity is >= V "
                           "(the thesis' value; the value used is printed)")
               ->capture_default_str(),
           "V", NumberRange::any())
        ->group(kMethodGroup);
    number(command.add_option("--sigma-max", s.sst.sigma_max,
                              "sst, hybrid: ... and its spread along its normal <= S scene units (default: 1.2% of "
                              "the scene's size, the thesis' 0.3 in its Sponza; the value used is printed)"),
           "S", NumberRange::at_least(0.0))
        ->group(kMethodGroup);
    number(command
               .add_option("--exact-clamp", s.exact_min_distance_fraction,
                           "exact: the 1/d^2 clamp's d_min as a fraction of the scene scale (every method's); 0: "
                           "unclamped, as a path tracer sums the light")
               ->capture_default_str(),
           "F", NumberRange::from(0.0, 1.0))
        ->group(kMethodGroup);
    whole_number(command
                     .add_option("--flc-levels", s.flc_levels,
                                 "flc: partition levels (the last level's VPLs light everything in front of them, "
                                 "so no light is dropped beyond D_N)")
                     ->capture_default_str(),
                 "N", 1, stages::kFlcMaxLevels)
        ->group(kMethodGroup);
    number(command.add_option("--flc-mu", s.flc_mu, "flc: ratio of consecutive levels' areas, S_k = S_0 MU^k")
               ->capture_default_str(),
           "MU", NumberRange::above(1.0))
        ->group(kMethodGroup);
    number(command
               .add_option("--flc-navg", s.flc_vpls_per_point,
                           "flc: about how many VPLs light each point (eq. 1; the paper's 64..1024): more VPLs, "
                           "less noise, more time")
               ->capture_default_str(),
           "A", NumberRange::above(0.0))
        ->group(kMethodGroup);
    whole_number(command
                     .add_option("--flc-subtiles", s.flc_subtiles,
                                 "flc: N x N interleaved sub-tiles (1: off): each VPL is splatted into one "
                                 "sub-tile (1/N^2 of the pixels), then untiled and blurred")
                     ->capture_default_str(),
                 "N", 1, stages::kFlcMaxSubtiles)
        ->group(kMethodGroup);

    one_of(command
               .add_option("--vpl-source", vpl_source_,
                           "where the VPLs come from. auto: brsm for --bounces 1 from punctual lights, else ir; "
                           "ir: instant radiosity, light paths through the scene, multi-bounce; brsm: bidirectional "
                           "reflective shadow maps, one bounce, placed where the camera sees their light (punctual "
                           "lights only); smc: sequential Monte Carlo instant radiosity: a set of --vpls VPLs "
                           "(default 2048) on the surfaces the camera sees indirectly, multi-bounce, kept across "
                           "frames; each frame moves at most --smc-max-moves of them")
               ->capture_default_str(),
           {"ir", "brsm", "smc", "auto"})
        ->group(kVplGroup);
    whole_number(command
                     .add_option("--vpls", s.vpl_paths,
                                 "ir: light paths traced (each leaves up to --bounces VPLs); brsm: VPLs over all "
                                 "lights, shared by power; smc: the set's size (at most " +
                                     std::to_string(stages::kSmcMaxBudget) + ", default 2048)")
                     ->capture_default_str(),
                 "N", 1, 1u << 24)
        ->group(kVplGroup);
    whole_number(
        command.add_option("--bounces", s.vpl_bounces, "ir, smc: surface hits per light path")->capture_default_str(),
        "B", 1, 16)
        ->group(kVplGroup);
    whole_number(command
                     .add_option("--smc-max-moves", s.smc.max_moves,
                                 "smc: VPLs that may leave the set per frame (the paper's M_max)")
                     ->capture_default_str(),
                 "M", 1, 1u << 20)
        ->group(kVplGroup);
    whole_number(
        command
            .add_option("--smc-resample", s.smc.resample_ratio, "smc: camera rays per candidate VPL (the paper's 16:1)")
            ->capture_default_str(),
        "R", 1, 1024)
        ->group(kVplGroup);
    whole_number(
        command.add_option("--smc-radiosity-samples", s.smc.radiosity_samples, "smc: paths per VPL radiosity estimate")
            ->capture_default_str(),
        "S", 1, 4096)
        ->group(kVplGroup);
    whole_number(command.add_option("--smc-warmup", s.smc_warmup, "smc: updates before the first frame (the paper's)")
                     ->capture_default_str(),
                 "W", 0, 100000)
        ->group(kVplGroup);
    whole_number(command
                     .add_option("--rsm-resolution", s.rsm_resolution,
                                 "brsm: texels along a shadow map face's side (1365 for point lights, whose cube "
                                 "map is 3 x 2 faces)")
                     ->capture_default_str(),
                 "R", 1, 2048)
        ->group(kVplGroup);
    whole_number(
        command.add_option("--brsm-samples", s.brsm.samples_per_texel, "brsm: G-buffer samples per shadow-map texel")
            ->capture_default_str(),
        "S", 1, 1024)
        ->group(kVplGroup);
    number(command
               .add_option("--brsm-defensive", s.brsm.defensive_fraction,
                           "brsm: share of the VPL pdf that follows flux alone (0 = pure BRSM, biased: light off "
                           "screen gets no VPLs)")
               ->capture_default_str(),
           "A", NumberRange::from(0.0, 1.0))
        ->group(kVplGroup);
    command.add_flag("--vpls-only", s.vpls_only, "write the VPLs over the dimmed direct image instead of a frame")
        ->group(kVplGroup);

    one_of(command
               .add_option("--direct", direct_,
                           "how direct light from emissive triangles, point and spot lights is sampled. tree: one "
                           "light tree over them all, a cut per 4 x 4 block and a traversal per cut node to one "
                           "light (stochastic lightcuts); flat: point and spot lights one by one, emitters drawn "
                           "by power; auto: tree when the scene has more than 8 such lights (the plan says which "
                           "and why); tree2: the tree in two levels, a bottom tree per mesh light under a top "
                           "tree. Directional lights are evaluated one by one either way")
               ->capture_default_str(),
           {"auto", "tree", "tree2", "flat"})
        ->group(kDirectGroup);
    whole_number(command
                     .add_option("--direct-spp", s.direct_samples,
                                 "samples per pixel of sampled direct light: flat: emitter samples; tree: cut "
                                 "nodes, one light sample each (at most 64)")
                     ->capture_default_str(),
                 "N", 1, 65536)
        ->group(kDirectGroup);
    whole_number(command
                     .add_option("--direct-interleave", s.direct_interleave,
                                 "tree: interleaved sampling over M x M sub-blocks of the 8 x 8 cut blocks (1: off; "
                                 "M divides 8, M^2 <= --direct-spp), reconstructed from similar neighbours")
                     ->capture_default_str(),
                 "M", 1, 8)
        ->group(kDirectGroup);

    command
        .add_option("--exposure", exposure_,
                    "the PNG's linear scale before the tone curve, or auto: the lit pixels' 95th luminance "
                    "percentile to 2.0 (about 0.96 on the display); the scale used is printed. HDR outputs (PFM, "
                    "EXR) are never scaled")
        ->capture_default_str()
        ->option_text("auto|E")
        ->check(CLI::Validator(
            [positive = number_check(NumberRange::above(0.0))](std::string& text) -> std::string {
                if (text == "auto" || positive(text).empty()) return "";
                return "expects auto or a positive number (a linear scale), got '" + text + "'";
            },
            "", "exposure"))
        ->group(kFilterGroup);
    whole_number(
        command.add_option("--seed", s.seed, "seed of the stochastic stages: the same seed gives the same image")
            ->capture_default_str(),
        "S", 0, UINT32_MAX)
        ->group(kFilterGroup);
    one_of(command
               .add_option("--denoise", denoise_,
                           "temporal (reprojected accumulation) or svgf (accumulation + the variance-guided "
                           "a-trous filter) on the indirect light; left out for exact")
               ->capture_default_str(),
           {"off", "temporal", "svgf"})
        ->group(kFilterGroup);
    number(command
               .add_option("--firefly-sigma", s.denoise_options.firefly_k_sigma,
                           "with --denoise: move accumulated indirect luminance above the neighbours' mean + K "
                           "sigma onto those neighbours (0: off); the share is printed")
               ->capture_default_str(),
           "K", NumberRange::at_least(0.0))
        ->group(kFilterGroup);
    command
        .add_flag("--all-stages", s.force_all_stages,
                  "run every stage the method can use, whatever the scene needs, and reuse nothing between "
                  "frames (the planner's baseline)")
        ->group(kFilterGroup);
    command
        .add_flag("--no-reuse", no_reuse_, "place the VPLs and build the trees every frame, even when nothing changed")
        ->group(kFilterGroup);
}

}  // namespace vplkit::cli
