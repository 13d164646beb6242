#include "denoise_setup.hpp"

#include "vplkit/stages/gbuffer.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <cmath>
#include <cstring>
#include <vector>

namespace vplkit::test {

glm::mat4 denoise_camera(const glm::vec3& eye, uint32_t width, uint32_t height) {
    const glm::mat4 view = glm::lookAt(eye, eye + glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
    return stages::vulkan_perspective(glm::radians(45.0f), float(width) / float(height), 0.1f, 100.0f) * view;
}

DenoiseGeometry plane_geometry(const glm::mat4& view_projection, uint32_t width, uint32_t height,
                               const PlaneScene& scene) {
    DenoiseGeometry g{DenoiseImage(width, height), DenoiseImage(width, height)};
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(view_projection));
    for (int y = 0; y < int(height); ++y) {
        for (int x = 0; x < int(width); ++x) {
            const float z = scene.depth(x, y);
            if (z == 0.0f) continue;
            const double ndc_x = (x + 0.5) / width * 2.0 - 1.0, ndc_y = (y + 0.5) / height * 2.0 - 1.0;
            glm::dvec4 near = inverse * glm::dvec4(ndc_x, ndc_y, 0.0, 1.0);
            glm::dvec4 far = inverse * glm::dvec4(ndc_x, ndc_y, 1.0, 1.0);
            const glm::dvec3 a = glm::dvec3(near) / near.w, b = glm::dvec3(far) / far.w;
            const double t = (double(z) - a.z) / (b.z - a.z);
            const glm::dvec3 p = a + t * (b - a);
            const glm::vec3 n = scene.normal(x, y);
            g.position.at(x, y) = {double(float(p.x)), double(float(p.y)), double(float(p.z)), 1.0};
            g.normal.at(x, y) = {double(n.x), double(n.y), double(n.z), 0.0};
        }
    }
    return g;
}

DenoiseImage to_float_precision(const DenoiseImage& image) {
    DenoiseImage out = image;
    for (auto& t : out.texels)
        for (double& v : t) v = double(float(v));
    return out;
}

Image float4_image(Context& ctx, uint32_t width, uint32_t height, const char* name) {
    return Image::create(ctx, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, name);
}

Image upload_image(Context& ctx, const DenoiseImage& image, const char* name) {
    Image out = float4_image(ctx, image.width, image.height, name);
    std::vector<Float4> texels(image.texels.size());
    for (size_t i = 0; i < texels.size(); ++i)
        for (int c = 0; c < 4; ++c) texels[i][c] = float(image.texels[i][c]);
    out.upload(texels);
    return out;
}

namespace {
// IEEE half from float, round to nearest even (inputs here are in [0, 1]).
uint16_t to_half(float value) {
    uint32_t bits;
    std::memcpy(&bits, &value, 4);
    const uint32_t sign = (bits >> 16) & 0x8000u;
    const int exponent = int((bits >> 23) & 0xff) - 127 + 15;
    uint32_t mantissa = bits & 0x7fffffu;
    if (exponent <= 0) return uint16_t(sign);  // flushed: the tests' albedos are 0 or >= 1e-2
    uint32_t half = sign | (uint32_t(exponent) << 10) | (mantissa >> 13);
    const uint32_t rest = mantissa & 0x1fffu;
    if (rest > 0x1000u || (rest == 0x1000u && (half & 1u))) ++half;
    return uint16_t(half);
}
double from_half(uint16_t h) {
    const int exponent = (h >> 10) & 0x1f;
    const double mantissa = h & 0x3ff;
    if (exponent == 0) return std::ldexp(mantissa, -24);
    return std::ldexp(1.0 + mantissa / 1024.0, exponent - 15) * ((h & 0x8000) ? -1.0 : 1.0);
}
}  // namespace

Image upload_albedo(Context& ctx, const DenoiseImage& albedo, const char* name) {
    Image out = Image::create(ctx, albedo.width, albedo.height, VK_FORMAT_R16G16B16A16_SFLOAT,
                              VK_IMAGE_USAGE_STORAGE_BIT, name);
    std::vector<std::array<uint16_t, 4>> texels(albedo.texels.size());
    for (size_t i = 0; i < texels.size(); ++i)
        for (int c = 0; c < 4; ++c) texels[i][c] = to_half(float(albedo.texels[i][c]));
    out.upload(texels);
    // The caller's reference must use the rounded values: check them here once.
    for (size_t i = 0; i < texels.size(); ++i)
        for (int c = 0; c < 4; ++c)
            if (std::abs(from_half(texels[i][c]) - albedo.texels[i][c]) > 1e-3 * albedo.texels[i][c] + 1e-7)
                throw std::runtime_error("upload_albedo: value not representable within 1e-3");
    return out;
}

DenoiseImage download_image(Image& image) {
    const auto texels = image.download<Float4>();
    DenoiseImage out(image.width(), image.height());
    for (size_t i = 0; i < texels.size(); ++i)
        for (int c = 0; c < 4; ++c) out.texels[i][c] = texels[i][c];
    return out;
}

double max_relative_error(const DenoiseImage& gpu, const DenoiseImage& reference, double floor, bool alpha) {
    double worst = 0.0;
    for (size_t i = 0; i < gpu.texels.size(); ++i)
        for (int c = 0; c < (alpha ? 4 : 3); ++c)
            worst = std::max(worst, std::abs(gpu.texels[i][c] - reference.texels[i][c]) /
                                        (std::abs(reference.texels[i][c]) + floor));
    return worst;
}

}  // namespace vplkit::test
