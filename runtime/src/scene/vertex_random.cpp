#include "vplkit/scene.hpp"

namespace vplkit::scene {

namespace {

// rng.glsl's pcg_hash (Jarzynski and Olano 2020): one LCG step, then the RXS-M-XS permutation.
uint32_t pcg_hash(uint32_t v) {
    const uint32_t state = v * 747796405u + 2891336453u;
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

}  // namespace

uint32_t vertex_random_value(uint32_t node, uint32_t mesh, uint32_t primitive, uint32_t vertex) {
    // Chained rather than summed, so (node, mesh) = (1, 2) and (2, 1) give unrelated values.
    return pcg_hash(vertex ^ pcg_hash(primitive ^ pcg_hash(mesh ^ pcg_hash(node))));
}

}  // namespace vplkit::scene
