// The options bench gi and bench direct share (bench_options.hpp).

#include "bench_options.hpp"

#include "cli_checks.hpp"
#include "device_options.hpp"

#include <algorithm>

namespace vplkit::cli {

void add_bench_scene_options(CLI::App& command, BenchSceneOptions& o, const std::string& scene_help) {
    add_device_options(command, o.context, false);
    command.add_option("--scene", o.scene, scene_help)->option_text("NAME|FILE");
    add_camera_options(command, o.camera_flags);
}

void add_bench_output_options(CLI::App& command, BenchSceneOptions& o, const BenchDefaults& d) {
    command
        .add_option_function<std::string>(
            "--out", [&o](const std::string& v) { o.out = v; },
            "output folder (default " + d.out_root + "/NAME, NAME the set-up or the file's stem)")
        ->option_text("DIR");
    const auto size_help = [&d](const char* what, uint32_t cpu, uint32_t gpu, uint32_t quick) {
        return std::string("image ") + what + " (default " + std::to_string(cpu) + " on a CPU device, " +
               std::to_string(gpu) + " on a GPU, " + std::to_string(quick) + " with --quick)";
    };
    whole_number(
        command.add_option_function<uint32_t>(
            "--width", [&o](uint32_t v) { o.width = v; }, size_help("width", d.cpu_width, d.gpu_width, d.quick_width)),
        "W", 1, 16384);
    whole_number(command.add_option_function<uint32_t>(
                     "--height", [&o](uint32_t v) { o.height = v; },
                     size_help("height", d.cpu_height, d.gpu_height, d.quick_height)),
                 "H", 1, 16384);
    whole_number(command.add_option_function<uint32_t>(
                     "--frames", [&o](uint32_t v) { o.frames = v; }, d.frames_help),
                 "F", d.min_frames, 100);
    command.add_flag("--quick", o.quick, d.quick_help);
    command.add_flag("--strict", o.strict,
                     "fail when the scene has a warning (a feature of the file vplkit skips or approximates)");
}

bool names_scene_file(const std::string& scene) {
    return scene.find('/') != std::string::npos || scene.ends_with(".gltf") || scene.ends_with(".glb");
}

std::string bench_scene_name(const std::string& scene) {
    return names_scene_file(scene) ? std::filesystem::path(scene).stem().string() : scene;
}

std::filesystem::path bench_out_folder(const BenchSceneOptions& o, const BenchDefaults& d) {
    return o.out ? std::filesystem::path(*o.out) : std::filesystem::path(d.out_root) / bench_scene_name(o.scene);
}

BenchSize bench_frame_size(const BenchSceneOptions& o, const BenchDefaults& d, const DeviceInfo& device) {
    const bool cpu =
        device.type_name.find("CPU") != std::string::npos || device.type_name.find("cpu") != std::string::npos;
    return {o.width.value_or(o.quick ? d.quick_width
                             : cpu   ? d.cpu_width
                                     : d.gpu_width),
            o.height.value_or(o.quick ? d.quick_height
                              : cpu   ? d.cpu_height
                                      : d.gpu_height)};
}

double median_of(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace vplkit::cli
