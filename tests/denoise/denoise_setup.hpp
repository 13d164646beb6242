#pragma once
// Synthetic inputs of the denoise tests: G-buffers of planes seen by a perspective camera (the
// runtime's Vulkan projection), uploaded as the passes read them and kept in double for the
// reference.

#include "denoise_reference.hpp"
#include "vplkit/context.hpp"
#include "vplkit/image.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <functional>

namespace vplkit::test {

using Float4 = std::array<float, 4>;
using reference::DenoiseGeometry;
using reference::DenoiseImage;

// A camera at `eye` looking down -z (45 degree vertical field, square pixels), its world ->
// Vulkan clip matrix.
glm::mat4 denoise_camera(const glm::vec3& eye, uint32_t width, uint32_t height);

// What a pixel sees: the first hit of its ray among the planes z = depth(x, y) (a per-pixel choice
// lets a test draw steps), with normal(x, y). A depth of 0 is background.
struct PlaneScene {
    std::function<float(int, int)> depth;  // the plane's z (negative: in front of the camera)
    std::function<glm::vec3(int, int)> normal;
};

// The G-buffer positions (the ray through each pixel centre meets z = depth) and normals.
DenoiseGeometry plane_geometry(const glm::mat4& view_projection, uint32_t width, uint32_t height,
                               const PlaneScene& scene);

// Rounded to float as the GPU will see it, so that the reference starts from the same numbers.
DenoiseImage to_float_precision(const DenoiseImage& image);

Image upload_image(Context& ctx, const DenoiseImage& image, const char* name);
Image float4_image(Context& ctx, uint32_t width, uint32_t height, const char* name);
// RGBA16F, as the G-buffer's albedo.
Image upload_albedo(Context& ctx, const DenoiseImage& albedo, const char* name);
DenoiseImage download_image(Image& image);

// Largest |gpu - reference| / (|reference| + floor) over rgb and a of covered texels.
double max_relative_error(const DenoiseImage& gpu, const DenoiseImage& reference, double floor, bool alpha = true);

}  // namespace vplkit::test
