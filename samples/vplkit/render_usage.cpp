// The usage of `vplkit render` and `vplkit plan`; render's lists the methods from the method
// table (gi_methods.hpp).

#include "camera_flags.hpp"
#include "cli.hpp"
#include "commands.hpp"

#include "vplkit/gi_methods.hpp"

#include <span>
#include <string>
#include <string_view>

namespace vplkit::cli {

namespace {

// {method names} and {method help} are replaced from the method table (gi_methods.hpp).
const char* const kRenderUsageText =
    "usage: vplkit render [--scene NAME|FILE] [--out IMAGE.png|.exr] [--width W] [--height H] [--camera N]\n"
    "       [--time T [--animation NAME|INDEX]]\n"
    "                     [--position X,Y,Z --target X,Y,Z [--up X,Y,Z]] [--fov DEG]\n"
    "                     [--sun DX,DY,DZ,R,G,B,I]... [--point X,Y,Z,R,G,B,I]... [--exposure auto|E]\n"
    "                     [--method {method names}] [--spp N] [--block K] [--interleave M]\n"
    "                     [--flc-levels N] [--flc-mu MU] [--flc-navg A] [--flc-subtiles N]\n"
    "                     [--traversal substitute|lightcuts] [--glossy-lobe auto|on|off] [--brdf gltf|lambert]\n"
    "                     [--gi-resolution full|half] [--nu-min V] [--sigma-max S]\n"
    "                     [--vpl-source auto|ir|brsm|smc] [--vpls N] [--bounces B] [--exact-clamp F]\n"
    "                     [--smc-max-moves M] [--smc-resample R] [--smc-radiosity-samples S] [--smc-warmup W]\n"
    "                     [--rsm-resolution R] [--brsm-samples S] [--brsm-defensive A] [--vpls-only]\n"
    "                     [--seed S] [--direct auto|tree|tree2|flat] [--direct-spp N] [--direct-interleave M]\n"
    "                     [--frames F] [--no-antialias] [--denoise off|temporal|svgf] [--firefly-sigma K]\n"
    "                     [--all-stages] [--no-reuse]\n"
    "                     [--out-hdr IMAGE.pfm|.exr] [--out-direct IMAGE.pfm] [--out-indirect IMAGE.pfm]\n"
    "                     [--stats FILE.json]\n"
    "                     [--device SEL] [--validation] [--strict]\n"
    "\n"
    "Renders one frame (G-buffer; direct light from punctual lights and emissive triangles with BVH\n"
    "shadow rays; indirect light by the chosen method; tone mapping) and prints the device used\n"
    "and the GPU time of every stage.\n"
    "  --scene S        a standard set-up from scenes/setups.txt (default: its default, 'cornell'),\n"
    "                   or a .gltf/.glb file (its own camera, or one framing the scene)\n"
    "  --out FILE       the tonemapped image, PNG (default vplkit.png); a .exr name writes the\n"
    "                   layered EXR below instead\n"
    "  --out-hdr FILE   also the linear radiance, PFM; or a layered OpenEXR file (.exr) of every\n"
    "                   layer the frame has: beauty, direct, indirect (with an indirect-light\n"
    "                   method), albedo, normal (world space), depth (along the camera's axis, in\n"
    "                   scene units, inf where no surface was drawn) and variance (with --denoise:\n"
    "                   the indirect light's luminance variance); channels beauty.R ... depth.Z,\n"
    "                   normal.X, variance.Y; radiance, depth, variance 32-bit floats (a sun-lit\n"
    "                   pixel can pass half's 65504), albedo and normal 16-bit\n"
    "  --stats FILE     also a JSON file: the device (lavapipe or not), the plans (each stage kept\n"
    "                   or left out and why), GPU times (frame_ms: the median frame's sum over\n"
    "                   every pass; per stage and per pass), the counters printed, the firefly\n"
    "                   share; a number that is not finite is written as null\n"
    "  --out-direct FILE, --out-indirect FILE   the linear direct / indirect parts, PFM\n"
    "  --method M       {method help}\n"
    "  --flc-levels N   flc: partition levels (default 8, at most 32; the last level's VPLs light\n"
    "                   everything in front of them, so no light is dropped beyond D_N)\n"
    "  --flc-mu MU      flc: ratio of consecutive levels' areas, S_k = S_0 MU^k (default 2, above 1)\n"
    "  --flc-navg A     flc: about how many VPLs light each point (eq. 1, default 64; the paper's\n"
    "                   64..1024): more VPLs, less noise, more time\n"
    "  --flc-subtiles N flc: N x N interleaved sub-tiles (default 1: off, at most 8): each VPL is\n"
    "                   splatted into one sub-tile (1/N^2 of the pixels), then untiled and blurred\n"
    "  --spp N          sst: traversals per pixel; rtslc, hybrid: the cut size, one traversal per cut\n"
    "                   node (default 8, at most 64); each is one shadow ray\n"
    "  --block K        rtslc, hybrid: pixels share a cut per K x K block (default 8, at most 32)\n"
    "  --interleave M   rtslc: interleaved sampling over M x M sub-blocks (default 1: off)\n"
    "  --traversal T    hybrid: below each cut node, substitute (default: the thesis' early-stop\n"
    "                   traversal) or lightcuts (rtslc's traversal to a leaf over hybrid's cuts)\n"
    "  --glossy-lobe G  sst, rtslc, hybrid: the glossy branch (seed 004 sec. 4.2: receivers smoother\n"
    "                   than roughness 0.5 sample the diffuse or the glossy lobe per sample, glossy to\n"
    "                   a leaf VPL); auto (default): on when a material of the scene can be that\n"
    "                   smooth (`vplkit plan` names them), else compiled out\n"
    "  --gi-resolution R   full (default) or half: indirect light at half resolution, joint\n"
    "                   bilateral upsampling to full\n"
    "  --nu-min V, --sigma-max S   sst, hybrid: a tree node is sampled as a whole when its normal\n"
    "                   similarity is >= V and its spread along its normal <= S scene units\n"
    "                   (defaults: 0.7, the thesis', and 1.2% of the scene's size, the thesis' 0.3\n"
    "                   in its Sponza; the value used is printed)\n"
    "  --vpl-source S   where the VPLs come from: auto (default): brsm for --bounces 1 from punctual\n"
    "                   lights, else ir; ir: instant radiosity, light paths through the scene,\n"
    "                   multi-bounce; brsm: bidirectional reflective shadow maps, one bounce, placed\n"
    "                   where the camera sees their light (punctual lights only); smc: sequential\n"
    "                   Monte Carlo instant radiosity (seed 001): a set of --vpls VPLs (default\n"
    "                   2048) on the surfaces the camera sees indirectly, multi-bounce, kept\n"
    "                   across frames; each frame moves at most --smc-max-moves of them (16)\n"
    "  --smc-max-moves M    smc: VPLs that may leave the set per frame (default 16, the paper's M_max)\n"
    "  --smc-resample R     smc: camera rays per candidate VPL (default 16, the paper's 16:1)\n"
    "  --smc-radiosity-samples S   smc: paths per VPL radiosity estimate (default 16)\n"
    "  --smc-warmup W   smc: updates before the first frame (default 100, the paper's)\n"
    "  --vpls N         ir: light paths traced (default 4096; each leaves up to --bounces VPLs);\n"
    "                   brsm: VPLs over all lights, shared by power (default 4096)\n"
    "  --bounces B      ir: surface hits per light path (default 2)\n"
    "  --rsm-resolution R   brsm: texels along a shadow map face's side (default 512, at most 2048;\n"
    "                   1365 for point lights, whose cube map is 3 x 2 faces)\n"
    "  --brsm-samples S     brsm: G-buffer samples per shadow-map texel (default 8)\n"
    "  --brsm-defensive A   brsm: share of the VPL pdf that follows flux alone, 0..1 (default 0.1;\n"
    "                   0 = pure BRSM, biased: light off screen gets no VPLs)\n"
    "  --vpls-only      write the VPLs over the dimmed direct image to --out instead of a frame\n"
    "  --width W        image width (default: the set-up's, else 640)\n"
    "  --height H       image height (default: the set-up's, else 360)\n"
    "  --camera N       use the file's camera N instead of the set-up's\n"
    "  --time T         pose the file's animations at T seconds (each channel holds its first and\n"
    "                   last keys outside them; default: the rest pose, with a warning)\n"
    "  --animation A    with --time: only animation A (its name or index; default: all of them)\n"
    "{camera flags}"
    "  --sun ...        add a directional light travelling along (DX,DY,DZ), colour RGB, I lux\n"
    "  --point ...      add a point light at (X,Y,Z), colour RGB, I candela\n"
    "  --exposure E     the PNG's linear scale before the tone curve, or auto (default): the lit\n"
    "                   pixels' 95th luminance percentile to 2.0 (about 0.96 on the display); the\n"
    "                   scale used is printed. HDR outputs (PFM, EXR) are never scaled\n"
    "  --brdf B         gltf (default): the file's metallic-roughness materials; lambert: every\n"
    "                   material a pure Lambertian of its base colour (for diffuse-only references)\n"
    "  --exact-clamp F  exact: the 1/d^2 clamp's d_min as a fraction of the scene scale (default\n"
    "                   0.01, every method's); 0: unclamped, as a path tracer sums the light\n"
    "  --seed S         seed of the stochastic stages: the same seed gives the same image (default 0)\n"
    "  --direct D       how direct light from emissive triangles, point and spot lights is sampled:\n"
    "                   tree: one light tree over them all, a cut per 4 x 4 block and a traversal\n"
    "                   per cut node to one light (stochastic lightcuts); flat: point and spot lights\n"
    "                   one by one, emitters drawn by power; auto (default): tree when the scene has\n"
    "                   more than 8 such lights (the plan says which and why); tree2: the tree in\n"
    "                   two levels, a bottom tree per mesh light under a top tree. Directional lights\n"
    "                   are evaluated one by one either way\n"
    "  --direct-spp N   samples per pixel of sampled direct light (default 16): flat: emitter\n"
    "                   samples; tree: cut nodes, one light sample each (at most 64)\n"
    "  --direct-interleave M   tree: interleaved sampling over M x M sub-blocks of the 8 x 8 cut\n"
    "                   blocks (default 1: off; M divides 8, M^2 <= --direct-spp), reconstructed\n"
    "                   from similar neighbours (an approximation, as rtslc's --interleave)\n"
    "  --all-stages     run every stage the method can use, whatever the scene needs, and reuse\n"
    "                   nothing between frames (the planner's baseline)\n"
    "  --no-reuse       place the VPLs and build the trees every frame, even when nothing changed\n"
    "  --denoise D      off (default), temporal (reprojected accumulation) or svgf (accumulation +\n"
    "                   the variance-guided a-trous filter) on the indirect light; left out for exact\n"
    "  --firefly-sigma K  with --denoise: move accumulated indirect luminance above the neighbours'\n"
    "                   mean + K sigma onto those neighbours (default 4; 0: off); the share is printed\n"
    "  --frames F       render the frame F times and print each stage's median time over frames\n"
    "                   2..F (the first pays for shader compiles); the image is the mean of the F\n"
    "                   frames on the static camera, each with new samples and its G-buffer at a\n"
    "                   sub-pixel offset (anti-aliasing; with --denoise the filter accumulates the\n"
    "                   indirect light itself)\n"
    "  --no-antialias   with --frames: every frame at the pixel centres (the image of one frame)\n"
    "  --device SEL     auto, gpu, cpu (lavapipe), an index, or part of a name\n"
    "  --validation     run with the Vulkan validation layer on\n"
    "  --strict         fail (exit 1, nothing written) when the scene has a warning: a feature of\n"
    "                   the file that vplkit skips or approximates (printed as 'warning: ...')\n";

// "direct (default): direct light only; or indirect light from VPLs by", then a method a line
// (wrapped at `column`): "exact: every VPL at every pixel with a shadow ray (the ground truth);".
std::string method_help(size_t column) {
    std::string text;
    const std::span<const GiMethodInfo> methods = gi_methods();
    for (size_t i = 0; i < methods.size(); ++i) {
        const GiMethodInfo& m = methods[i];
        if (m.vpls == GiVpls::none) {
            text += wrapped(
                std::string(m.name) + " (default): " + std::string(m.summary) + "; or indirect light from VPLs by",
                column, column);
        } else {
            text += (text.empty() ? "" : "\n" + std::string(column, ' ')) +
                    wrapped(std::string(m.name) + ": " + std::string(m.summary) + (i + 1 < methods.size() ? ";" : ""),
                            column, column);
        }
    }
    return text;
}

}  // namespace

std::string render_usage() {
    std::string names;
    for (const GiMethodInfo& m : gi_methods()) names += (names.empty() ? "" : "|") + std::string(m.name);
    std::string text = kRenderUsageText;
    const std::string_view camera_slot = "{camera flags}";
    text.replace(text.find(camera_slot), camera_slot.size(), kCameraFlagsUsage);
    const std::string_view names_slot = "{method names}", help_slot = "{method help}";
    text.replace(text.find(names_slot), names_slot.size(), names);
    const size_t help = text.find(help_slot);
    const size_t column = help - (text.rfind('\n', help) + 1);
    text.replace(help, help_slot.size(), method_help(column));
    return text;
}

const char* const kPlanUsage =
    "usage: vplkit plan [render's options: --scene NAME|FILE --method M --vpl-source S --bounces B\n"
    "                   --gi-resolution R --sun ... --point ... --strict ...\n"
    "                   --position X,Y,Z --target X,Y,Z --up X,Y,Z --fov DEG]\n"
    "\n"
    "Prints the stages a frame with these options would run, and for every stage kept or left out\n"
    "the reason (the effects planner, runtime/include/vplkit/planner.hpp). Reads the scene; no\n"
    "device work. `vplkit render` prints the plan's one-line summary. The scene's warnings (what\n"
    "the file states that vplkit skips or approximates) are printed first; --strict fails on them.\n";

}  // namespace vplkit::cli
