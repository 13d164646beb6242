// `vplkit render`: one frame of a scene (a standard set-up's name or a glTF file) with direct
// light, written as PNG (and linear PFM on request), with the device and per-stage GPU times.

#include "cli.hpp"
#include "commands.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_setups.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <unistd.h>

namespace vplkit::cli {

const char* const kRenderUsage =
    "usage: vplkit render [--scene NAME|FILE] [--out IMAGE.png] [--width W] [--height H] [--camera N]\n"
    "                     [--sun DX,DY,DZ,R,G,B,I]... [--point X,Y,Z,R,G,B,I]... [--exposure E]\n"
    "                     [--method direct|exact] [--vpls N] [--bounces B] [--seed S] [--emissive-samples N]\n"
    "                     [--out-hdr IMAGE.pfm] [--out-direct IMAGE.pfm] [--out-indirect IMAGE.pfm]\n"
    "                     [--device SEL] [--validation]\n"
    "\n"
    "Renders one frame (G-buffer; direct light from punctual lights and emissive triangles with BVH\n"
    "shadow rays; indirect light by the chosen method; tone mapping) and prints the device used\n"
    "and the GPU time of every stage.\n"
    "  --scene S        a standard set-up from scenes/setups.txt (default: its default, 'cornell'),\n"
    "                   or a .gltf/.glb file (its own camera, or one framing the scene)\n"
    "  --out FILE       the tonemapped image, PNG (default vplkit.png)\n"
    "  --out-hdr FILE   also the linear radiance, PFM\n"
    "  --out-direct FILE, --out-indirect FILE   the linear direct / indirect parts, PFM\n"
    "  --method M       direct (default): direct light only; exact: plus indirect light from\n"
    "                   instant-radiosity VPLs, every VPL at every pixel with a shadow ray (ground truth)\n"
    "  --vpls N         light paths traced for VPLs (default 4096; each leaves up to --bounces VPLs)\n"
    "  --bounces B      surface hits per light path (default 2)\n"
    "  --width W        image width (default: the set-up's, else 640)\n"
    "  --height H       image height (default: the set-up's, else 360)\n"
    "  --camera N       use the file's camera N instead of the set-up's\n"
    "  --sun ...        add a directional light travelling along (DX,DY,DZ), colour RGB, I lux\n"
    "  --point ...      add a point light at (X,Y,Z), colour RGB, I candela\n"
    "  --exposure E     linear exposure before the tone curve (default 1)\n"
    "  --seed S         seed of the stochastic stages: the same seed gives the same image (default 0)\n"
    "  --emissive-samples N  area-light samples per pixel for emissive triangles (default 16)\n"
    "  --device SEL     auto, gpu, cpu (lavapipe), an index, or part of a name\n"
    "  --validation     run with the Vulkan validation layer on\n";

namespace {

// Fails before any rendering when a file could not be written there.
void check_output(const std::string& option, const std::filesystem::path& path, const std::string& extension) {
    if (path.extension() != extension) {
        throw UsageError(option + " expects a " + extension + " file name, got '" + path.string() + "'");
    }
    const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
    if (!std::filesystem::is_directory(folder)) {
        throw UsageError(option + ": the folder " + folder.string() + " does not exist");
    }
}

float parse_exposure(const std::string& text) {
    size_t used = 0;
    float value = 0.0f;
    try {
        value = std::stof(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || !std::isfinite(value) || value <= 0.0f) {
        throw UsageError("--exposure expects a positive number, got '" + text + "'");
    }
    return value;
}

}  // namespace

int run_render(Args& args) {
    ContextOptions context_options;
    if (auto device = args.value("--device")) context_options.device = *device;
    context_options.validation = args.flag("--validation");
    const std::string scene_arg = args.value("--scene").value_or("");
    const std::filesystem::path out = args.value("--out").value_or("vplkit.png");
    const auto out_hdr = args.value("--out-hdr");
    const auto out_direct = args.value("--out-direct");
    const auto out_indirect = args.value("--out-indirect");
    std::optional<uint32_t> width, height, camera;
    if (auto text = args.value("--width")) width = parse_whole_number("--width", *text, 16384);
    if (auto text = args.value("--height")) height = parse_whole_number("--height", *text, 16384);
    if (auto text = args.value("--camera")) camera = parse_index("--camera", *text, 1u << 20);
    std::vector<scene::Light> extra_lights;
    // A malformed light is a command-line mistake: usage, exit 2.
    try {
        while (auto spec = args.value("--sun")) extra_lights.push_back(scene::parse_sun(*spec));
        while (auto spec = args.value("--point")) extra_lights.push_back(scene::parse_point(*spec));
    } catch (const Error& e) {
        throw UsageError(e.what());
    }
    RenderSettings settings;
    if (auto text = args.value("--exposure")) settings.exposure = parse_exposure(*text);
    if (auto text = args.value("--seed")) settings.seed = parse_index("--seed", *text, UINT32_MAX);
    if (auto text = args.value("--emissive-samples")) settings.emissive_samples = parse_whole_number("--emissive-samples", *text, 65536);
    if (auto text = args.value("--method")) {
        if (*text == "direct") settings.method = GiMethod::none;
        else if (*text == "exact") settings.method = GiMethod::exact;
        else throw UsageError("--method expects direct or exact (sst, rtslc and hybrid are not built yet), got '" + *text + "'");
    }
    if (auto text = args.value("--vpls")) settings.vpl_paths = parse_whole_number("--vpls", *text, 1u << 24);
    if (auto text = args.value("--bounces")) settings.vpl_bounces = parse_whole_number("--bounces", *text, 16);
    args.finish();
    check_output("--out", out, ".png");
    if (out_hdr) check_output("--out-hdr", *out_hdr, ".pfm");
    if (out_direct) check_output("--out-direct", *out_direct, ".pfm");
    if (out_indirect) check_output("--out-indirect", *out_indirect, ".pfm");

    // The scene: a set-up name, or a file.
    const auto load_start = std::chrono::steady_clock::now();
    scene::LoadOptions load_options;
    load_options.camera = camera;
    scene::Scene scene;
    std::string described;
    const bool is_file = scene_arg.find('/') != std::string::npos || scene_arg.ends_with(".gltf") || scene_arg.ends_with(".glb");
    if (is_file) {
        scene = scene::load_gltf(scene_arg, load_options);
        described = scene_arg;
        settings.width = width.value_or(640);
        settings.height = height.value_or(360);
    } else {
        const scene::Setups setups = scene::load_setups(VPLKIT_SETUPS_FILE);
        const scene::Setup& setup = scene_arg.empty() ? setups.default_setup() : setups.find(scene_arg);
        scene = scene::load_setup_scene(setup, load_options);
        described = setup.name + " (" + setup.scene.string() + ")";
        settings.width = width.value_or(setup.width ? setup.width : 640);
        settings.height = height.value_or(setup.height ? setup.height : 360);
    }
    scene.lights.insert(scene.lights.end(), extra_lights.begin(), extra_lights.end());
    const double load_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start).count();

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
    const RenderedImage image = renderer.render(scene.camera(), settings);
    if (settings.method == GiMethod::exact) {
        std::printf("indirect: %u VPLs from %u light paths x %u bounces\n", image.vpl_count, settings.vpl_paths,
                    settings.vpl_bounces);
        if (image.dropped_pixels > 0) {
            std::printf("warning: %u pixels had a non-finite VPL contribution left out\n", image.dropped_pixels);
        }
    }
    if (image.non_finite_pixels > 0) {
        throw Error("render: " + std::to_string(image.non_finite_pixels) +
                    " pixels came out NaN or infinite; no image written (this is a bug: please report it)");
    }

    std::printf("%ux%u, GPU time per stage:\n", image.width, image.height);
    double total = 0.0;
    for (const PassTiming& t : image.timings) {
        std::printf("  %-22s %9.3f ms\n", t.name.c_str(), t.gpu_ms);
        total += t.gpu_ms;
    }
    std::printf("  %-22s %9.3f ms\n", "total", total);

    write_png(out, image.width, image.height, image.rgba8);
    std::printf("wrote %s\n", out.string().c_str());
    if (out_hdr) {
        write_pfm(*out_hdr, image.width, image.height, image.radiance);
        std::printf("wrote %s\n", out_hdr->c_str());
    }
    if (out_direct) {
        write_pfm(*out_direct, image.width, image.height, image.direct);
        std::printf("wrote %s\n", out_direct->c_str());
    }
    if (out_indirect) {
        write_pfm(*out_indirect, image.width, image.height, image.indirect);
        std::printf("wrote %s\n", out_indirect->c_str());
    }
    return 0;
}

}  // namespace vplkit::cli
