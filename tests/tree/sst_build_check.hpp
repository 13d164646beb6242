#pragma once
// The SST build tests' harness (test_build_sst.cpp, test_build_sst_surfaces.cpp): VPL sets padded
// as gather_leaves.comp leaves them, build_sst.comp run on them, and the node-by-node comparison
// with the double reference (tests/reference/sst_reference) within its error bound.

#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/sst.hpp"
#include "sst_reference.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace vplkit::sst_test {

namespace ref = vplkit::reference;
using vplkit::shaders::SstNode;
using vplkit::shaders::vec3;
using vplkit::shaders::Vpl;
using vplkit::stages::SstOptions;

inline constexpr SstOptions kThesis{0.7f, 0.3f};  // the thesis sec. 5.2 (the default)
inline constexpr SstOptions kPaper{0.5f, 0.1f};   // the SST paper sec. 6

struct Scene {
    std::vector<Vpl> leaves;  // leaf_count(count) entries; the tail is bogus
    uint32_t count = 0;
};

Vpl make_vpl(std::array<float, 3> p, std::array<float, 3> n, std::array<float, 3> flux);
std::array<float, 3> unit(double x, double y, double z);

// Pads with all-zero bogus leaves (what gather_leaves.comp writes).
Scene padded(std::vector<Vpl> vpls);

struct RandomScene {
    uint32_t count = 100;
    uint32_t seed = 1;
    std::array<double, 3> center{0.0, 0.0, 0.0};
    double extent = 1.0;
    double flux_lo = 0.1, flux_hi = 10.0;
    bool log_flux = false;
};

// Surfaces laid out in leaf order the way a Morton sort would: 2x2 blocks of 2x2 blocks, so each
// subtree is a square patch. floor: z = noise; bent: a cylinder of radius `radius` around y.
std::vector<Vpl> patch(uint32_t side_log2, double spacing, double radius, double z_noise, uint32_t seed,
                       std::array<double, 3> origin);

Scene random_scene(const RandomScene& s);
std::vector<ref::SstLeaf> reference_leaves(const Scene& scene);
ref::SstThresholds thresholds(const SstOptions& options);

// Builds the tree on the GPU over garbage-filled nodes and counters; checks the counters.
std::vector<SstNode> build_on_gpu(const Scene& scene, const SstOptions& options = {});

bool all_finite(const SstNode& n);
bool is_all_zero(const SstNode& n);
bool near3(const vec3& gpu, const ref::Double3& r, double tol);
bool exact3(const vec3& gpu, const ref::Double3& r);

struct Comparison {
    uint32_t nodes = 0;
    uint32_t ambiguous_flags = 0;
    uint32_t suitable = 0;  // GPU nodes flagged suitable (non-empty)
    uint32_t fallbacks = 0;
};

// Compares the stored nodes (inner nodes, or the root record of a one-VPL tree) with the
// reference tree over the same leaves, each field within kSafety x its bound (sst_build_check.cpp).
Comparison compare_with_reference(const Scene& scene, const std::vector<SstNode>& gpu, const SstOptions& options);
Comparison build_and_compare(const Scene& scene, const SstOptions& options = {});

}  // namespace vplkit::sst_test
