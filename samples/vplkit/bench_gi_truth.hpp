#pragma once
// bench gi's ground truth: the exact frame of the set-up at the bench's size and VPL set, kept in
// the cache folder under a hash of everything it depends on (the key, stored beside and compared).

#include <filesystem>
#include <vector>

namespace vplkit {
class Renderer;
struct RenderSettings;
namespace scene {
struct Scene;
struct Setup;
}  // namespace scene
}  // namespace vplkit

namespace vplkit::cli {

struct GroundTruth {
    std::vector<float> rgb;       // tonemapped, sRGB / 255
    std::vector<float> radiance;  // linear
    std::filesystem::path png;    // the tonemapped frame in the cache
    bool cached = false;          // read from the cache, not rendered
    double wall_ms = 0.0;         // rendered: the host wall clock it took
};

// The exact frame (`base` with method exact) from `cache` when its key matches, else rendered,
// with progress on stderr, and cached. Throws vplkit::Error when the frame has non-finite pixels.
GroundTruth bench_ground_truth(Renderer& renderer, const scene::Setup& setup, const scene::Scene& scene,
                               const RenderSettings& base, const std::filesystem::path& cache);

}  // namespace vplkit::cli
