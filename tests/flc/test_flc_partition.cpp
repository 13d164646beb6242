// The partition of unity of vplkit/flc_partition.glsl (the FLC paper eqs. 10-18) through test shaders
// (shaders/partition_values.comp, shaders/candidate_weights.comp).
//
// Values: f~^k(d) against the double reference at distances on and between the D_k, within 1e-5
// (D_k = D_0 mu^(k/2) through float pow, then one division: a few float roundings of values in
// [0, 1]); F^k = S_k f~^k within 1e-5 relative to S_k. The reference's own sum over k is 1 at
// every finite distance, D_N and beyond included (the last level reaches everything in front of
// its triangle: with D_{N+1} = D_N a receiver past D_N got no light), to 1e-12.
// Expectation: a VPL of level k stands for F^k = S_k f~^k(d) at a receiver, and the level is
// drawn with P(k) = A / S_k, so E[F^level(d)] / A = sum_k f~^k(d) = 1 at every distance. Over
// n = triangles x seeds draws (independent per triangle and seed: see flc_candidates.comp), the
// mean of F / A must be within 4 sigma / sqrt(n) of that (sigma: the samples' standard deviation),
// at two sample counts, so that a bias (which does not shrink) shows as the count grows.
// Behind the triangle every weight must be exactly 0: a VPL lights only the half-space in front.

#include "flc_reference.hpp"
#include "flc_test_mesh.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/flc_test/candidate_weights.hpp"
#include "vplkit/flc_test/partition_values.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

namespace {

using vplkit::stages::FlcPartition;
using namespace flc_test;

FlcPartition test_partition() {
    FlcPartition p;
    p.level_count = 4;
    p.s0 = 0.05f;
    p.d0 = 0.5f;
    p.mu = 2.0f;
    return p;
}

vplkit::reference::FlcParameters reference_of(const FlcPartition& p) {
    return {int(p.level_count), double(p.s0), double(p.d0), double(p.mu)};
}

vplkit::Buffer storage(VkDeviceSize bytes, const char* name) {
    return vplkit::Buffer::create(vplkit::test::context(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  vplkit::MemoryUse::device, name);
}

// Distances on, between and beyond the D_k, and 0.
std::vector<float> test_distances(const vplkit::reference::FlcParameters& p) {
    std::vector<float> d{0.0f};
    const double last = vplkit::reference::flc_influence_distance(p, p.level_count - 1);
    for (int i = 1; i <= 200; ++i) d.push_back(float(1.2 * last * i / 200.0));
    for (int k = 0; k < p.level_count; ++k) d.push_back(float(vplkit::reference::flc_influence_distance(p, k)));
    d.push_back(std::numeric_limits<float>::infinity());
    return d;
}

}  // namespace

TEST_CASE("flc partition: f^k and F^k match the reference and sum to one at every distance") {
    namespace shader = vplkit::flc_test::partition_values;
    using Value = vplkit::flc_test::PartitionValue;
    vplkit::Context& ctx = vplkit::test::context();
    for (FlcPartition partition :
         {test_partition(), FlcPartition{1, 0.2f, 1.0f, 3.0f}, FlcPartition{6, 1e-3f, 0.1f, 1.4f}}) {
        const auto p = reference_of(partition);
        CAPTURE(p.level_count);
        const std::vector<float> distances = test_distances(p);
        const uint32_t count = uint32_t(distances.size()) * partition.level_count;
        auto distance_buffer = storage(distances.size() * sizeof(float), "flc distances");
        auto value_buffer = storage(count * sizeof(Value), "flc partition values");
        distance_buffer.upload(distances);
        const auto& pipeline = ctx.pipeline<shader::Pipeline>();
        vplkit::PassList passes("flc partition values test");
        shader::Bindings b;
        b.distances = distance_buffer.descriptor();
        b.values = value_buffer.descriptor();
        passes.add("flc partition values", {vplkit::Use::read(distance_buffer), vplkit::Use::write(value_buffer)},
                   [&](VkCommandBuffer cmd) {
                       shader::Push push{};
                       push.distance_count = uint32_t(distances.size());
                       push.level_count = int32_t(partition.level_count);
                       push.s0 = partition.s0;
                       push.d0 = partition.d0;
                       push.mu = partition.mu;
                       pipeline.dispatch(cmd, b, push, count);
                   });
        passes.run(ctx);
        const auto values = value_buffer.download<Value>(count);
        for (size_t i = 0; i < distances.size(); ++i) {
            const double d = distances[i];
            CAPTURE(d);
            double reference_sum = 0.0, gpu_sum = 0.0;
            for (int k = 0; k < p.level_count; ++k) {
                const Value& v = values[i * p.level_count + k];
                const double f = vplkit::reference::flc_partition_weight(p, k, d);
                CHECK(f >= 0.0);
                CHECK(f <= 1.0);
                CHECK(std::abs(v.weight - f) <= 1e-5);
                CHECK(std::abs(v.area_weight - vplkit::reference::flc_vpl_area_weight(p, k, d)) <=
                      1e-5 * vplkit::reference::flc_level_area(p, k));
                reference_sum += f;
                gpu_sum += v.weight;
            }
            const double expected = std::isinf(d) ? 0.0 : 1.0;  // beyond D_N too; behind the plane nothing
            CHECK(std::abs(reference_sum - expected) <= 1e-12);
            CHECK(std::abs(gpu_sum - expected) <= 1e-5);
        }
    }
}

namespace {

struct WeightSamples {
    std::vector<double> sum, sum_squares;  // of F / A, per distance
    std::vector<size_t> nonzero;           // per distance
    size_t n = 0;                          // per distance
    std::vector<double> max_distance_error;
};

// Every triangle of `mesh` gets, per distance d_j, one receiver at support distance d_j (on its
// normal for even triangles, 60 degrees off it for odd ones) and one behind it; the candidate
// pass and candidate_weights.comp run per seed.
WeightSamples sample_weights(const Mesh& mesh, const FlcPartition& partition, const std::vector<double>& distances,
                             uint32_t first_seed, uint32_t seeds) {
    namespace shader = vplkit::flc_test::candidate_weights;
    using Weight = vplkit::flc_test::CandidateWeight;
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t per = uint32_t(distances.size()) + 1;  // the last one behind
    const uint32_t triangles = mesh.triangle_count();
    const uint32_t point_count = triangles * per;
    WeightSamples out;
    out.sum.assign(per, 0.0);
    out.sum_squares.assign(per, 0.0);
    out.nonzero.assign(per, 0);
    out.max_distance_error.assign(per, 0.0);
    auto candidate_buffer = storage(triangles * sizeof(vplkit::shaders::FlcCandidate), "flc candidates");
    auto point_buffer = storage(point_count * sizeof(float) * 4, "flc receivers");
    auto weight_buffer = storage(point_count * sizeof(Weight), "flc weights");
    const auto& pipeline = ctx.pipeline<shader::Pipeline>();
    for (uint32_t s = 0; s < seeds; ++s) {
        const auto candidates = run_candidates(mesh, partition, first_seed + s);
        std::vector<float> points;
        for (uint32_t t = 0; t < triangles; ++t) {
            const glm::dvec3 y(candidates[t].position.x, candidates[t].position.y, candidates[t].position.z);
            const glm::dvec3 n(candidates[t].normal.x, candidates[t].normal.y, candidates[t].normal.z);
            const glm::dvec3 side = glm::normalize(glm::cross(n, glm::dvec3(0.3, 0.5, 0.8)));
            const double angle = (t % 2 == 0) ? 0.0 : M_PI / 3.0;
            const glm::dvec3 direction = std::cos(angle) * n + std::sin(angle) * side;
            for (uint32_t j = 0; j <= distances.size(); ++j) {
                // |x - y| = d cos(angle) gives support distance d (eq. 14).
                const glm::dvec3 x = j < distances.size() ? y + direction * (distances[j] * std::cos(angle))
                                                          : y - n * distances[0] + side * 0.1;
                points.insert(points.end(), {float(x.x), float(x.y), float(x.z), 1.0f});
            }
        }
        candidate_buffer.upload(candidates);
        point_buffer.upload(points);
        vplkit::PassList passes("flc candidate weights test");
        shader::Bindings b;
        b.candidates = candidate_buffer.descriptor();
        b.points = point_buffer.descriptor();
        b.weights = weight_buffer.descriptor();
        passes.add(
            "flc candidate weights",
            {vplkit::Use::read(candidate_buffer), vplkit::Use::read(point_buffer), vplkit::Use::write(weight_buffer)},
            [&](VkCommandBuffer cmd) {
                shader::Push push{};
                push.point_count = point_count;
                push.points_per_candidate = per;
                push.level_count = int32_t(partition.level_count);
                push.s0 = partition.s0;
                push.d0 = partition.d0;
                push.mu = partition.mu;
                pipeline.dispatch(cmd, b, push, point_count);
            });
        passes.run(ctx);
        const auto weights = weight_buffer.download<Weight>(point_count);
        for (uint32_t t = 0; t < triangles; ++t) {
            for (uint32_t j = 0; j < per; ++j) {
                const Weight& w = weights[t * per + j];
                REQUIRE(std::isfinite(w.area_weight));
                const double ratio = double(w.area_weight) / double(candidates[t].area);
                out.sum[j] += ratio;
                out.sum_squares[j] += ratio * ratio;
                out.nonzero[j] += w.area_weight != 0.0f;
                if (j < distances.size()) {
                    out.max_distance_error[j] =
                        std::max(out.max_distance_error[j], std::abs(w.distance - distances[j]) / distances[j]);
                } else {
                    CHECK(std::isinf(w.distance));
                }
            }
        }
    }
    out.n = size_t(triangles) * seeds;
    return out;
}

}  // namespace

TEST_CASE("flc partition: the sum over levels of F^k, in expectation over the decimation, is the triangle's area") {
    const FlcPartition partition = test_partition();
    const auto p = reference_of(partition);
    const double last = vplkit::reference::flc_influence_distance(p, p.level_count - 1);
    // Every band of the partition, D_N itself, and beyond D_N.
    const std::vector<double> distances{0.2 * p.d0,  0.99 * p.d0, 1.3 * p.d0, 0.5 * (p.d0 + last),
                                        0.98 * last, 1.05 * last, 3.0 * last};
    // Triangles of area 0.6 S~_N: every level is drawn often.
    const double area = 0.6 * vplkit::reference::flc_divergence_area(p);
    const float cell = float(std::sqrt(2.0 * area));
    const Mesh mesh = grid(24, cell);  // 1152 triangles
    for (uint32_t seeds : {4u, 24u}) {
        CAPTURE(seeds);
        const WeightSamples s = sample_weights(mesh, partition, distances, 500, seeds);
        for (size_t j = 0; j < distances.size(); ++j) {
            CAPTURE(distances[j]);
            CHECK(s.max_distance_error[j] < 1e-4);
            const double mean = s.sum[j] / double(s.n);
            const double variance = std::max(0.0, s.sum_squares[j] / double(s.n) - mean * mean);
            const double bound = 4.0 * std::sqrt(variance / double(s.n));
            MESSAGE("d " << distances[j] << ", " << s.n << " draws: mean F / A " << mean << ", bound " << bound);
            CHECK(bound > 0.0);
            CHECK(std::abs(mean - 1.0) <= bound);
        }
        CHECK(s.nonzero.back() == 0);  // behind the triangle
    }
}
