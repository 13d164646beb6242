#pragma once
// The VPL tracing tests' harness (test_vpl_tracing.cpp, test_vpl_tracing_paths.cpp): scenes made
// of boxes, quads and point lights, trace_vpls.comp run on them, and the closed-box check of the
// mean flux per bounce over seeds.

#include "vplkit/bvh_gpu.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/vpl_tracing_buffers.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <numbers>
#include <vector>

namespace vplkit::vpl_tracing_test {

using vplkit::scene::Scene;
using vplkit::stages::VplTracingOptions;
inline constexpr double kPi = std::numbers::pi;

uint32_t add_material(Scene& scene, glm::vec3 rho, float metallic = 0.0f);
void add_triangle(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material);
void add_quad(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material);

// The six faces of [lo, hi], each split in two triangles (windings mixed on purpose: light is
// two-sided for the tracer).
void add_box(Scene& scene, glm::vec3 lo, glm::vec3 hi, uint32_t material);

inline const glm::vec3 kBoxLo{-1.0f, -0.75f, -0.5f}, kBoxHi{1.0f, 0.75f, 0.5f};

vplkit::scene::Light point_light(glm::vec3 position, glm::vec3 color, float intensity);

struct Traced {
    std::vector<vplkit::shaders::Vpl> vpls;
    std::vector<uint32_t> bounces;
};

// Traces `scene` with `options`; the BVH's ids are the scene's triangle indices.
class Tracer {
public:
    explicit Tracer(const Scene& scene);

    Traced run(const VplTracingOptions& options);

    const vplkit::VplSources& sources() const { return sources_; }
    const vplkit::GpuBvh& bvh() const { return bvh_; }

private:
    vplkit::GpuBvh bvh_;
    vplkit::VplSources sources_;
};

using Rgb = std::array<double, 3>;

// Per bounce 1..max_bounces: the summed VPL flux (index 0 unused).
std::vector<Rgb> flux_per_bounce(const Traced& t, uint32_t max_bounces);

// Mean over seeds of the per-bounce flux against expected[k] (k = 1..max_bounces), per channel.
void check_mean_flux(Tracer& tracer, VplTracingOptions options, uint32_t seeds, const std::vector<Rgb>& expected);

bool finite(const vplkit::shaders::vec3& v);
glm::dvec3 to_d(const vplkit::shaders::vec3& v);

}  // namespace vplkit::vpl_tracing_test
