#pragma once
// The harness of the rtslc tests (test_rtslc.cpp, test_rtslc_hard_cases.cpp): a floor (y = 0) of
// 16 x 16 pixels with tilted shading normals and varied materials, VPLs on a ceiling, on a wall
// (some grazing), below the floor (behind every pixel), facing away, free, and some of zero flux;
// the GPU side that builds the trees once and runs add_rtslc_passes; and the unbiasedness check
// against the double reference (tests/reference/rtslc_reference.cpp).

#include "vplkit/buffer.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/image.hpp"
#include "vplkit/rtslc_scratch.hpp"
#include "vplkit/stages/gi_counters.hpp"
#include "vplkit/stages/rtslc.hpp"
#include "vplkit/vpl_trees.hpp"
#include "vplkit_test/context.hpp"
#include "rtslc_reference.hpp"
#include "synthetic_scene.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace vplkit::rtslc_test {

namespace ref = vplkit::reference;
namespace stages = vplkit::stages;
using vplkit::test::d3;
using vplkit::test::half_round;
using vplkit::test::Pixel;
using vplkit::test::shading_point;
using vplkit::test::TestVpl;
using Texel = std::array<float, 4>;

struct Setup {
    uint32_t width = 16, height = 16;
    float scale = 1.0f;
    std::vector<Pixel> pixels;
    std::vector<glm::vec3> triangles;  // three vertices each
    std::vector<TestVpl> vpls;
    glm::vec3 camera{0.0f, 3.0f, 4.0f};
};

// Floor [-3s, 3s]^2 at y = 0 (scene scale 3s), pixels on it.
Setup floor_setup(float s = 1.0f, uint32_t width = 16, uint32_t height = 16);

// `count` VPLs at scale s with flux ~ flux_scale (radiance is scale-invariant for flux ~ s^2):
// cycling through ceiling, wall (the first ones grazing), below the floor, facing away, free,
// and black (zero flux).
std::vector<TestVpl> floor_vpls(uint32_t count, float s, float flux_scale, uint32_t seed = 11);

Setup standard_setup(uint32_t count = 100, float s = 1.0f, float flux = 1.0f);

// The GPU side: G-buffer, BVH, VPLs and their trees, built once; render() runs the RTSLC passes.
struct Gpu {
    vplkit::Context& ctx = vplkit::test::context();
    const Setup& setup;
    vplkit::GbufferImages gbuffer;
    vplkit::GpuBvh bvh;
    vplkit::Buffer vpls;
    vplkit::VplTrees trees;
    vplkit::Image indirect;
    vplkit::Buffer counters;
    std::optional<vplkit::RtslcScratch> scratch;

    explicit Gpu(const Setup& s);

    struct Frame {
        std::vector<Texel> image;
        stages::GiCounts counts;
        std::vector<uint32_t> cuts, representatives;
        size_t passes = 0;
    };

    Frame render(const stages::RtslcOptions& options, bool read_cuts = false);
    std::vector<ref::RtslcNode> tree() const;
};

double scene_min_distance(const Setup& setup);

// The exact unshadowed sum at every pixel (0 on background).
std::vector<ref::Vec3> unshadowed(const Setup& setup);

struct Unbiasedness {
    double largest_z = 0.0;  // over pixels and channels, sigma from the reference's probabilities
    double rms_z = 0.0;
    double largest_sample_z = 0.0;  // the same with sigma estimated from the samples
    double image_z = 0.0;           // of the image's summed radiance, sigma from the samples
    int pixels = 0, exact_pixels = 0;
};

// The mean over `seeds` frames (seed 1000 + i, frame i) against the exact unshadowed sum over
// every VPL, checked (doctest) per pixel and channel and over the image to |z| < z_limit;
// rtslc_setup.cpp says how sigma is taken.
Unbiasedness check_unbiased(Gpu& gpu, stages::RtslcOptions options, int seeds, double z_limit);

stages::RtslcOptions no_shadows(uint32_t spp = 8, uint32_t block = 8);

}  // namespace vplkit::rtslc_test
