// VPL trees over a count only the GPU knows (stages/element_count.hpp): the VPLs sit in a buffer
// of some capacity whose slots past the count hold bright garbage, and keys, sort, leaves, light
// tree and SST read the count from a buffer when they run. The host count's trees are the
// reference: with the same power-of-two leaf count the trees, and so every sampler's image, must
// be equal to the bit (the samplers then tell the padding by its data instead of its index);
// with a larger capacity (a deeper tree, mostly padding) the real leaves and the root's sums
// must agree and sst must stay unbiased. The count is clamped to the capacity, and a count of
// zero gives black, finite light.

#include "sampling_setup.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using namespace vplkit::sampling_test;
namespace shaders = vplkit::shaders;

namespace {

bool same_bits(const void* a, const void* b, size_t bytes) {
    return std::memcmp(a, b, bytes) == 0;
}

bool same(const shaders::vec3& a, const shaders::vec3& b) {
    return same_bits(&a, &b, sizeof(a));
}

// Field by field: the structs' padding bytes hold whatever the memory held.
bool same(const shaders::Vpl& a, const shaders::Vpl& b) {
    return same(a.position, b.position) && same(a.normal, b.normal) && same(a.flux, b.flux);
}

bool same(const shaders::SstNode& a, const shaders::SstNode& b) {
    return same(a.mean, b.mean) && same_bits(&a.intensity, &b.intensity, 4) && same(a.normal, b.normal) &&
           same_bits(&a.nu, &b.nu, 4) && same(a.variance, b.variance) && a.flags == b.flags &&
           same(a.box_lo, b.box_lo) && a.leaf_count == b.leaf_count && same(a.box_hi, b.box_hi) &&
           same(a.colour, b.colour);
}

bool same(const Texel& a, const Texel& b) {
    return same_bits(a.data(), b.data(), sizeof(a));
}

template <class T>
bool same_vectors(const std::vector<T>& a, const std::vector<T>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!same(a[i], b[i])) return false;
    }
    return true;
}

bool all_zero(const shaders::Vpl& v) {
    const shaders::vec3 zero{0.0f, 0.0f, 0.0f};
    return same(v.position, zero) && same(v.normal, zero) && same(v.flux, zero);
}

}  // namespace

TEST_CASE("GPU VPL count: within the host count's leaf count every sampler draws the same image") {
    const Scene scene = room(12, 10, 700);  // 700 and 1000 VPLs both fill 1024 leaves
    struct Case {
        const char* name;
        Method method;
        vplkit::stages::HybridTraversal traversal;
    };
    for (const Case& c : {Case{"sst", Method::sst, {}}, Case{"hybrid", Method::hybrid, {}},
                          Case{"hybrid lightcuts", Method::hybrid, vplkit::stages::HybridTraversal::lightcuts},
                          Case{"rtslc", Method::rtslc, {}}}) {
        CAPTURE(std::string(c.name));
        RunOptions options;
        options.method = c.method;
        options.traversal = c.traversal;
        options.samples_per_pixel = 4;
        options.seed = 7;
        const Rendered host = render(scene, options);
        options.gpu_count_capacity = 1000;
        const Rendered gpu = render(scene, options);
        REQUIRE(host.leaf_count == 1024);
        REQUIRE(gpu.leaf_count == 1024);
        CHECK(same_vectors(host.leaves, gpu.leaves));
        CHECK(same_vectors(host.sst, gpu.sst));
        CHECK(same_vectors(host.image, gpu.image));
        CHECK(host.counts.traversals == gpu.counts.traversals);
        double sum = 0.0;
        for (const Texel& t : gpu.image) sum += t[0] + t[1] + t[2];
        CHECK(sum > 0.0);  // the room is lit: equal images are not two black ones
    }
}

TEST_CASE("GPU VPL count: a capacity past the count's leaf count keeps the real leaves and the root's light") {
    const Scene scene = room(8, 6, 200);
    RunOptions options;
    options.method = Method::sst;
    const Rendered host = render(scene, options);
    options.gpu_count_capacity = 2048;  // 2048 leaves against the host's 256
    const Rendered gpu = render(scene, options);
    REQUIRE(gpu.leaf_count == 2048);
    for (size_t i = 0; i < gpu.leaves.size(); ++i) {
        CAPTURE(i);
        if (i < 200) {
            REQUIRE(same(host.leaves[i], gpu.leaves[i]));
        } else {
            REQUIRE(all_zero(gpu.leaves[i]));
        }
    }
    const shaders::SstNode& a = host.sst[0];
    const shaders::SstNode& b = gpu.sst[0];
    CHECK(b.leaf_count == 200);
    CHECK(b.intensity == doctest::Approx(a.intensity).epsilon(1e-5));
    for (int k = 0; k < 3; ++k) {
        CHECK((&b.colour.x)[k] == doctest::Approx((&a.colour.x)[k]).epsilon(1e-5));
    }
    CHECK(same(b.box_lo, a.box_lo));
    CHECK(same(b.box_hi, a.box_hi));
}

TEST_CASE("GPU VPL count: sst over a mostly padded tree stays unbiased") {
    const Scene scene = room(8, 6, 200);
    RunOptions options;
    options.method = Method::sst;
    options.samples_per_pixel = 2;
    options.visibility = false;
    options.sst.nu_min = 2.0f;  // every traversal reaches a leaf: importance sampling, no bias
    // 256 seeds as test_sampling.cpp's host-count check: sst's rare heavy draws need them (at 128,
    // the host's own tree once read z = 6 at one pixel).
    options.gpu_count_capacity = 2048;
    const MeanCheck check = check_mean(scene, options, 256, exact(scene, false));
    MESSAGE("sst over a padded tree: " << check.checked << " values, worst z " << check.worst_z);
    CHECK(check.checked > 100);
    CHECK(check.outside == 0);
}

TEST_CASE("GPU VPL count: a count past the capacity is the capacity, a count of zero is darkness") {
    const Scene scene = room(8, 6, 300);
    RunOptions options;
    options.method = Method::hybrid;
    options.seed = 3;
    const Rendered host = render(scene, options);
    options.gpu_count_capacity = 300;
    options.gpu_count = 5000;  // a producer that counted attempts past its room
    const Rendered clamped = render(scene, options);
    CHECK(same_vectors(host.image, clamped.image));

    for (Method method : {Method::sst, Method::hybrid, Method::rtslc}) {
        options.method = method;
        options.gpu_count = 0;
        const Rendered dark = render(scene, options);
        bool black = true;
        for (const Texel& t : dark.image) black = black && t[0] == 0.0f && t[1] == 0.0f && t[2] == 0.0f;
        CHECK(black);
        CHECK(dark.sst[0].leaf_count == 0);
    }
}
