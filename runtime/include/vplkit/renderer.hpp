#pragma once
// A whole frame of direct light: the G-buffer raster pass, direct light from punctual lights and
// from emissive triangles (area-light sampling) with BVH shadow rays, the tonemap; what `vplkit render` runs. Scene data is uploaded and the BVH built once, at
// construction; render() can then be called for any camera and size.

#include "vplkit/bvh_gpu.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/direct_emissive.hpp"
#include "vplkit/stages/direct_light.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace vplkit {

class Context;

// How indirect light is computed.
enum class GiMethod {
    none,   // direct light only
    exact,  // every VPL at every pixel with a shadow ray each: the ground truth
};

struct RenderSettings {
    uint32_t width = 640;
    uint32_t height = 360;
    float exposure = 1.0f;          // linear scale before the tone curve
    glm::vec3 background{0.0f};     // radiance where no surface was drawn
    uint32_t emissive_samples = 16; // area-light samples per pixel for emissive triangles
    uint32_t seed = 0;              // the same seed gives the same image
    GiMethod method = GiMethod::none;
    uint32_t vpl_paths = 4096;      // light paths traced for VPLs (instant radiosity)
    uint32_t vpl_bounces = 2;       // surface hits per path at most
    // Called during long indirect-light work with (done, total) units of work.
    std::function<void(uint32_t done, uint32_t total)> progress;
};

struct RenderedImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba8;      // tonemapped sRGB, rows top to bottom
    std::vector<float> radiance;     // linear RGB, 3 floats per pixel, rows top to bottom: direct + indirect
    std::vector<float> direct;       // the direct part alone (same layout)
    std::vector<float> indirect;     // the indirect part alone (zero with GiMethod::none)
    uint32_t vpl_count = 0;          // VPLs the indirect light came from
    uint32_t dropped_pixels = 0;     // pixels where a non-finite VPL contribution was left out
    std::vector<PassTiming> timings; // GPU time per pass
    uint32_t non_finite_pixels = 0;  // shown magenta in rgba8; a correct frame has none
};

class Renderer {
 public:
    // `scene` must outlive the renderer (the VPL tracer reads its lights and materials).
    // Throws vplkit::Error when the scene has no light at all (no punctual light and no emissive
    // triangle), naming the scene: its image could only be black.
    Renderer(Context& context, const scene::Scene& scene);

    // Throws vplkit::Error for a zero size or a bad exposure.
    RenderedImage render(const scene::Camera& camera, const RenderSettings& settings);

    double bvh_build_ms() const { return bvh_build_ms_; }
    const Bvh& bvh() const { return bvh_; }
    uint32_t light_count() const { return lights_.count; }
    uint32_t emitter_count() const { return emitters_.count; }

 private:
    Context& context_;
    GpuScene scene_;
    Bvh bvh_;
    GpuBvh gpu_bvh_;
    stages::GpuLights lights_;
    stages::GpuEmitters emitters_;
    const scene::Scene& scene_source_;  // for the VPL sources, uploaded on first use
    double bvh_build_ms_ = 0.0;
};

}  // namespace vplkit
