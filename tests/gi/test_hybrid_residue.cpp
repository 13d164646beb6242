// hybrid's converged residue: many frames of new samples over the same VPLs,
// averaged, against the exact sum over those VPLs (DESIGN.md, Tests, Convergence). What remains
// after many frames is bias; rtslc (unbiased) at the same samples per pixel and frames is the
// yardstick: its block error is the noise left, and hybrid's may exceed it only by what its blur
// (substitutes at a suitable depth, blended cuts) costs.
//
// The room (sampling_setup.hpp): 32 x 24 floor points with tilted normals, 256 VPLs on a ceiling
// (coplanar clusters the SST substitutes), a wall beside the floor, free ones and ones below it,
// an occluder; 64 frames of 8 samples per pixel, 8 x 8 cut blocks, thesis thresholds, shadows.
// Measured (lavapipe), mean / 4 x 4-block error / brightest pixel over exact's:
//   rtslc                  1.0007 / 0.0155 / 1.10
//   main before the fixes: hybrid 1.0170 / 0.0563 (3.6x rtslc's) / 0.86,
//                          hybrid-lightcuts 0.9994 / 0.0295 (1.9x) / 1.02
//   after (one blended cut per pixel, substitutes only far from their cluster, defensive child
//   probabilities): hybrid 1.0048 / 0.0316 (2.0x) / 0.97, hybrid-lightcuts 0.9992 / 0.0224
//   (1.4x) / 0.88;
//   a suitable node evaluated by one of its VPLs drawn by intensity instead of the Gaussian
//   substitute (hybrid_gi.comp, hybrid_add_cluster_sample): hybrid 1.0002 / 0.0250 (1.6x) / 0.94;
//   hybrid-lightcuts with rtslc's bound as its cuts' split order and rtslc's lobe MIS (the glossy
//   case below): 0.9968 / 0.0207 (1.34x) / 1.01.
// At 256 frames (the second test): rtslc 1.0002 / 0.0103; hybrid with the substitute 1.0036 /
// 0.0204 (1.97x rtslc's), with the VPL drawn by intensity 0.9999 / 0.0125 (1.21x);
// hybrid-lightcuts 1.0014 / 0.0124 (1.19x).
// The bounds: the mean within 1% (the DESIGN's energy rule at this noise: rtslc's is 0.07% off);
// hybrid's block error within 2.5x rtslc's and hybrid-lightcuts' within 1.4x (the fixes' values
// with room for the 64 frames' spread, and below the values before), the brightest pixel within
// 1.1x rtslc's or exact's. At 64 frames both block errors are still mostly noise (hybrid's
// 1.6x falls to 1.2x by 256 frames). hybrid-lightcuts' 1.34x here is one draw of 64 frames: over
// ten other seed sets of 128 frames its block error is 1.04x rtslc's in RMS (1.10x before).

#include "sampling_setup.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace {

using namespace vplkit::sampling_test;
namespace ref = vplkit::reference;

using Image = std::vector<std::array<double, 3>>;

// The mean over `frames` seeds (1000, 1001, ...) of the method's frame, and each pixel channel's
// variance across the frames; no sample dropped.
struct Frames {
    Image mean;
    Image variance;
};

Frames average(const Scene& scene, RunOptions options, uint32_t frames) {
    Frames out{Image(scene.pixels.size(), {0.0, 0.0, 0.0}), Image(scene.pixels.size(), {0.0, 0.0, 0.0})};
    for (uint32_t f = 0; f < frames; ++f) {
        options.seed = 1000 + f;
        const Rendered r = render(scene, options);
        REQUIRE(r.counts.dropped_samples == 0);
        REQUIRE(r.counts.cut_short == 0);
        for (size_t i = 0; i < out.mean.size(); ++i) {
            for (int c = 0; c < 3; ++c) {
                out.mean[i][c] += r.image[i][c];
                out.variance[i][c] += double(r.image[i][c]) * r.image[i][c];
            }
        }
    }
    for (size_t i = 0; i < out.mean.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            out.mean[i][c] /= frames;
            out.variance[i][c] = std::max(out.variance[i][c] / frames - out.mean[i][c] * out.mean[i][c], 0.0);
        }
    }
    return out;
}

struct Residue {
    double mean = 0.0;       // image mean / exact's (covered pixels)
    double block = 0.0;      // relative RMSE of k x k block means (covered pixels) over exact's image mean
    double brightest = 0.0;  // brightest pixel's luminance / exact's brightest
    double noise = 0.0;      // one frame's noise: sqrt(sum of the pixels' variances / sum of exact's squares)
};

double luminance(const std::array<double, 3>& v) {
    return 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
}

Residue residue(const Scene& scene, const Frames& frames, const std::vector<ref::Vec3>& truth, uint32_t k) {
    const Image& image = frames.mean;
    const uint32_t bw = (scene.width + k - 1) / k, bh = (scene.height + k - 1) / k;
    std::vector<std::array<double, 3>> a(bw * bh, {0, 0, 0}), b(bw * bh, {0, 0, 0});
    std::vector<uint32_t> count(bw * bh, 0);
    double sum_a = 0.0, sum_b = 0.0, max_a = 0.0, max_b = 0.0;
    double variance = 0.0, square = 0.0;
    uint32_t covered = 0;
    for (uint32_t y = 0; y < scene.height; ++y) {
        for (uint32_t x = 0; x < scene.width; ++x) {
            const size_t i = size_t(y) * scene.width + x;
            if (!scene.pixels[i].covered) continue;
            const size_t block = (y / k) * bw + x / k;
            ++count[block];
            ++covered;
            const std::array<double, 3> t = {truth[i][0], truth[i][1], truth[i][2]};
            for (int c = 0; c < 3; ++c) {
                a[block][c] += image[i][c];
                b[block][c] += t[c];
                sum_a += image[i][c];
                sum_b += t[c];
                variance += frames.variance[i][c];
                square += t[c] * t[c];
            }
            max_a = std::max(max_a, luminance(image[i]));
            max_b = std::max(max_b, luminance(t));
        }
    }
    double err = 0.0;
    uint32_t values = 0;
    for (size_t block = 0; block < a.size(); ++block) {
        if (count[block] == 0) continue;
        for (int c = 0; c < 3; ++c) {
            const double d = (a[block][c] - b[block][c]) / count[block];
            err += d * d;
            ++values;
        }
    }
    const double mean_b = sum_b / (3.0 * covered);
    return {sum_a / sum_b, std::sqrt(err / values) / mean_b, max_a / max_b, std::sqrt(variance / square)};
}

// The residue of `frames` frames at 8 spp in 8 x 8 blocks, per 4 x 4 block (`glossy`: every
// receiver smoother than the default threshold chooses a lobe, gi_lobe.glsl).
Residue converged_residue(const Scene& scene, const std::vector<ref::Vec3>& truth, Method method, uint32_t frames,
                          vplkit::stages::HybridTraversal traversal = RunOptions{}.traversal, bool glossy = false) {
    RunOptions options;
    options.samples_per_pixel = 8;
    options.block_size = 8;
    options.method = method;
    options.traversal = traversal;
    options.glossy.enabled = glossy;
    return residue(scene, average(scene, options, frames), truth, 4);
}

}  // namespace

TEST_CASE("hybrid: many frames' mean against exact, per 4x4 block and brightest pixel, within bounds from rtslc's") {
    const Scene scene = room(32, 24, 256);
    const auto truth = exact(scene, true);
    constexpr uint32_t kFrames = 64;
    const Residue rtslc = converged_residue(scene, truth, Method::rtslc, kFrames);
    const Residue hybrid = converged_residue(scene, truth, Method::hybrid, kFrames);
    const Residue lightcuts =
        converged_residue(scene, truth, Method::hybrid, kFrames, vplkit::stages::HybridTraversal::lightcuts);
    MESSAGE(kFrames << " frames of 8 spp, 4x4 blocks: rtslc mean " << rtslc.mean << " block " << rtslc.block
                    << " brightest " << rtslc.brightest << "; hybrid mean " << hybrid.mean << " block " << hybrid.block
                    << " brightest " << hybrid.brightest << "; hybrid-lightcuts mean " << lightcuts.mean << " block "
                    << lightcuts.block << " brightest " << lightcuts.brightest);
    CHECK(hybrid.mean == doctest::Approx(1.0).epsilon(0.01));
    CHECK(lightcuts.mean == doctest::Approx(1.0).epsilon(0.01));
    CHECK(hybrid.block <= 2.5 * rtslc.block);
    CHECK(lightcuts.block <= 1.4 * rtslc.block);
    CHECK(hybrid.brightest <= std::max(rtslc.brightest, 1.0) * 1.1);
}

// The converged residue itself: 256 frames, where the Gaussian substitute left hybrid's block
// error at 1.97x rtslc's (a bias: the substitute's position lit through the visibility of an
// independently drawn VPL; 1.55x even when substitutes were used only 3 extents from x) and the
// VPL drawn by intensity leaves 1.21x, hybrid-lightcuts' 1.19x (the target for hybrid:
// 1.25x). Bound 1.35x: the measured value with room for the frames' spread, below the substitute's.
TEST_CASE("hybrid: 256 frames' mean against exact, per 4x4 block, within 1.35x rtslc's block error") {
    const Scene scene = room(32, 24, 256);
    const auto truth = exact(scene, true);
    constexpr uint32_t kFrames = 256;
    const Residue rtslc = converged_residue(scene, truth, Method::rtslc, kFrames);
    const Residue hybrid = converged_residue(scene, truth, Method::hybrid, kFrames);
    MESSAGE(kFrames << " frames of 8 spp, 4x4 blocks: rtslc mean " << rtslc.mean << " block " << rtslc.block
                    << "; hybrid mean " << hybrid.mean << " block " << hybrid.block << " ("
                    << hybrid.block / rtslc.block << "x) brightest " << hybrid.brightest);
    CHECK(hybrid.mean == doctest::Approx(1.0).epsilon(0.005));
    CHECK(hybrid.block <= 1.35 * rtslc.block);
    CHECK(hybrid.brightest <= std::max(rtslc.brightest, 1.0) * 1.1);
}

// hybrid-lightcuts' noise on glossy receivers: one frame's noise (the pixels' variance across 64
// frames) against rtslc's in the glossy room, smooth receivers choosing a lobe. Before, its cuts
// were split by eq. 5.2 and its traversal weighed one lobe per sample (the lobe split): 1.49x
// rtslc's noise; with rtslc's lobe MIS (sst_traverse_lightcuts_lobe_mis) alone 1.46x (1.34x over
// 256 frames); with rtslc's bound as the split order too (hybrid_cut.comp) 0.71x (1.02x over 256
// frames). Bound 1.15x: the fix's value with room for the 64 frames' spread, below the value
// before; hybrid (unchanged, 1.08x) within 1.25x.
TEST_CASE("hybrid-lightcuts: one frame's noise in the glossy room within 1.15x rtslc's") {
    const Scene scene = glossy_room(32, 24, 256);
    const auto truth = exact(scene, true);
    constexpr uint32_t kFrames = 64;
    const auto lightcuts = vplkit::stages::HybridTraversal::lightcuts;
    const Residue rtslc = converged_residue(scene, truth, Method::rtslc, kFrames, RunOptions{}.traversal, true);
    const Residue hybrid = converged_residue(scene, truth, Method::hybrid, kFrames, RunOptions{}.traversal, true);
    const Residue hlc = converged_residue(scene, truth, Method::hybrid, kFrames, lightcuts, true);
    MESSAGE(kFrames << " frames of 8 spp, glossy room: noise rtslc " << rtslc.noise << ", hybrid-lightcuts "
                    << hlc.noise << " (" << hlc.noise / rtslc.noise << "x), hybrid " << hybrid.noise << " ("
                    << hybrid.noise / rtslc.noise << "x); means " << rtslc.mean << " " << hlc.mean << " "
                    << hybrid.mean);
    CHECK(hlc.mean == doctest::Approx(1.0).epsilon(0.02));
    CHECK(hlc.noise <= 1.15 * rtslc.noise);
    CHECK(hybrid.noise <= 1.25 * rtslc.noise);
}
