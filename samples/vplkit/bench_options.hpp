#pragma once
// What `vplkit bench gi` and `bench direct` read alike: the device, --scene (a standard set-up or a
// glTF file) with the camera flags, --out, --width, --height, --frames, --quick and --strict, each
// benchmark with its own defaults; and how they resolve (the output folder, the frame size).

#include "camera_flags.hpp"

#include <CLI/CLI.hpp>

#include "vplkit/context.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vplkit::cli {

struct BenchSceneOptions {
    ContextOptions context;
    std::string scene;  // --scene: a set-up name or a .gltf/.glb file
    CameraFlags camera_flags;
    std::optional<std::string> out;
    std::optional<uint32_t> width, height, frames;
    bool quick = false, strict = false;
};

// A benchmark's defaults, as its help states them.
struct BenchDefaults {
    std::string out_root;  // "out/bench": the folder is OUT_ROOT/NAME
    uint32_t quick_width = 0, quick_height = 0, cpu_width = 0, cpu_height = 0, gpu_width = 0, gpu_height = 0;
    uint32_t min_frames = 1;  // the fewest frames a point may take
    std::string frames_help;  // "frames per point (default 3, ...)"
    std::string quick_help;   // what --quick does
};

// The device options, --scene (`scene_help`) and the camera flags.
void add_bench_scene_options(CLI::App& command, BenchSceneOptions& o, const std::string& scene_help);
// --out, --width, --height, --frames, --quick and --strict.
void add_bench_output_options(CLI::App& command, BenchSceneOptions& o, const BenchDefaults& defaults);

// --scene names a file (a path, or a .gltf/.glb name) rather than a set-up.
bool names_scene_file(const std::string& scene);
// The set-up's name, or the file's stem.
std::string bench_scene_name(const std::string& scene);
// --out, or OUT_ROOT/NAME.
std::filesystem::path bench_out_folder(const BenchSceneOptions& o, const BenchDefaults& defaults);

// The frame size: --width and --height, else the defaults for --quick, a CPU device or a GPU.
struct BenchSize {
    uint32_t width = 0, height = 0;
};
BenchSize bench_frame_size(const BenchSceneOptions& o, const BenchDefaults& defaults, const DeviceInfo& device);

double median_of(std::vector<double> values);

}  // namespace vplkit::cli
