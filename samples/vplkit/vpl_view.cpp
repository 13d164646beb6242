#include "vpl_view.hpp"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>

namespace vplkit::cli {

namespace {

// A VPL nearer than this fraction behind the G-buffer's surface counts as on it (it lies on a
// surface; float positions from two rasterizations differ by far less).
constexpr float kSurfaceTolerance = 1e-3f;

void blend(std::vector<uint8_t>& rgba, uint32_t width, uint32_t height, int x, int y, glm::vec3 colour, float alpha) {
    if (x < 0 || y < 0 || x >= int(width) || y >= int(height)) return;
    uint8_t* p = &rgba[(size_t(y) * width + x) * 4];
    for (int c = 0; c < 3; ++c) p[c] = uint8_t(std::lround(p[c] * (1.0f - alpha) + 255.0f * colour[c] * alpha));
}

}  // namespace

VplView draw_vpl_view(const RenderedImage& image, const glm::mat4& view_projection, glm::vec3 eye) {
    const uint32_t w = image.width, h = image.height;
    VplView view;
    view.rgba8.resize(size_t(w) * h * 4);
    auto position = [&](uint32_t x, uint32_t y) {
        const float* g = &image.gbuffer_position[(size_t(y) * w + x) * 4];
        return glm::vec3(g[0], g[1], g[2]);
    };
    auto covered = [&](uint32_t x, uint32_t y) { return image.gbuffer_position[(size_t(y) * w + x) * 4 + 3] > 0.5f; };
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            const uint8_t* p = &image.rgba8[i * 4];
            float grey = 0.6f * (0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]);
            // Surfaces in shadow would be black: a faint shading by their facing (normal from the
            // G-buffer positions' differences) keeps the geometry readable there.
            if (x + 1 < w && y + 1 < h && covered(x, y) && covered(x + 1, y) && covered(x, y + 1)) {
                const glm::vec3 n =
                    glm::cross(position(x + 1, y) - position(x, y), position(x, y + 1) - position(x, y));
                const glm::vec3 to_eye = eye - position(x, y);
                const float facing =
                    std::abs(glm::dot(n, to_eye)) / std::max(1e-30f, glm::length(n) * glm::length(to_eye));
                if (std::isfinite(facing)) grey = std::max(grey, 16.0f + 40.0f * facing);
            }
            const auto g8 = uint8_t(std::lround(std::min(grey, 255.0f)));
            view.rgba8[i * 4 + 0] = view.rgba8[i * 4 + 1] = view.rgba8[i * 4 + 2] = g8;
            view.rgba8[i * 4 + 3] = 255;
        }
    }
    // Dots a few pixels wide at 640 pixels across, one pixel in small images.
    const int radius = int(std::max(0.0f, std::floor(float(std::max(w, h)) / 400.0f)));
    for (const VplPoint& vpl : image.vpls) {
        const glm::vec4 clip = view_projection * glm::vec4(vpl.position, 1.0f);
        if (!(clip.w > 0.0f)) {
            ++view.off_screen;
            continue;
        }
        const float px = (clip.x / clip.w * 0.5f + 0.5f) * float(w), py = (clip.y / clip.w * 0.5f + 0.5f) * float(h);
        if (!(px >= 0.0f && py >= 0.0f && px < float(w) && py < float(h))) {
            ++view.off_screen;
            continue;
        }
        const int x = int(px), y = int(py);
        const float* g = &image.gbuffer_position[(size_t(y) * w + x) * 4];
        const float vpl_distance = glm::length(vpl.position - eye);
        const bool hidden =
            g[3] > 0.5f && glm::length(glm::vec3(g[0], g[1], g[2]) - eye) < vpl_distance * (1.0f - kSurfaceTolerance);
        const float peak = std::max({vpl.flux.x, vpl.flux.y, vpl.flux.z});
        const glm::vec3 colour = peak > 0.0f && std::isfinite(peak) ? vpl.flux / peak : glm::vec3(1.0f, 0.0f, 1.0f);
        if (hidden) {
            ++view.hidden;
            blend(view.rgba8, w, h, x, y, colour, 0.35f);
            continue;
        }
        ++view.visible;
        for (int dy = -radius; dy <= radius; ++dy) {
            for (int dx = -radius; dx <= radius; ++dx) blend(view.rgba8, w, h, x + dx, y + dy, colour, 1.0f);
        }
    }
    return view;
}

}  // namespace vplkit::cli
