#pragma once
// The synthetic scene harness the gi suite's exact, sampling and rtslc tests share: a G-buffer
// given pixel by pixel, a triangle list for the BVH and shadow rays, and VPLs, uploaded for the
// GPU stages and converted to the double reference's types (vpl_reference.hpp, ray_reference.hpp).
// Each test file keeps its own scene generator; only these mechanics are shared. Namespace vplkit::test: it
// serves the tests, and the GPU half is not a reference.

#include "vpl_reference.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/gbuffer_images.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace vplkit {
class Context;
}

namespace vplkit::test {

// One G-buffer texel. The defaults are a background texel; generators set every field they use.
struct Pixel {
    bool covered = false;
    glm::vec3 position{0.0f}, normal{0.0f, 1.0f, 0.0f}, geometric{0.0f, 1.0f, 0.0f}, albedo{0.0f};
    float roughness = 0.5f, metallic = 0.0f;
};

struct TestVpl {
    glm::vec3 position, normal, flux;
};

// The value a float stores as after the G-buffer's half-float albedo: generators round albedo
// with it so that the reference shades what the GPU reads.
float half_round(float v);

reference::Vec3 d3(glm::vec3 v);

struct GpuSyntheticScene {
    vplkit::GbufferImages gbuffer;
    GpuBvh bvh;
    Buffer vpls;  // shaders::Vpl, in the given order
};

// The G-buffer (width x height pixels, row by row; emission 0), the BVH of `triangles` (three
// vertices each) and the VPL buffer. An empty VPL list uploads one zero VPL so that the buffer
// exists: the count the stages take is vpls.size() all the same.
GpuSyntheticScene upload(Context& context, uint32_t width, uint32_t height, std::span<const Pixel> pixels,
                         std::span<const glm::vec3> triangles, std::span<const TestVpl> vpls);

reference::ShadingPoint shading_point(const Pixel& p);
std::vector<reference::VplDesc> reference_vpls(std::span<const TestVpl> vpls);
std::vector<reference::Triangle> reference_triangles(std::span<const glm::vec3> triangles);

}  // namespace vplkit::test
