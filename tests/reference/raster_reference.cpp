#include "raster_reference.hpp"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vplkit::reference {
namespace {

struct TextureRead {
    glm::dvec4 value{1.0};
    bool ambiguous = false;
};

// Nearest texel of level 0 with repeat wrapping; `srgb` decodes RGB (alpha is always linear).
TextureRead read_texture(const scene::Scene& scene, int32_t texture, glm::dvec2 uv, bool srgb, glm::dvec4 fallback,
                         double texel_tolerance) {
    TextureRead r;
    if (texture == scene::kNoTexture) {
        r.value = fallback;
        return r;
    }
    const scene::Image& image = scene.images.at(scene.textures.at(size_t(texture)).image);
    const double x = uv.x * image.width, y = uv.y * image.height;
    auto near_border = [&](double t) { return std::abs(t - std::round(t)) < texel_tolerance; };
    r.ambiguous = near_border(x) || near_border(y);
    auto wrap = [](double t, uint32_t n) {
        const int64_t i = int64_t(std::floor(t)) % int64_t(n);
        return uint32_t(i < 0 ? i + n : i);
    };
    const size_t at = (size_t(wrap(y, image.height)) * image.width + wrap(x, image.width)) * 4;
    for (int c = 0; c < 4; ++c) {
        const uint8_t code = image.rgba[at + c];
        r.value[c] = (srgb && c < 3) ? srgb_to_linear(code) : code / 255.0;
    }
    return r;
}

}  // namespace

double srgb_to_linear(uint8_t code) {
    const double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

std::vector<GbufferTexel> rasterize_gbuffer(const scene::Scene& scene, const glm::dmat4& view_projection,
                                            const glm::dvec3& viewer, uint32_t width, uint32_t height,
                                            const RasterTolerances& tolerances) {
    std::vector<GbufferTexel> out(size_t(width) * height);
    const size_t triangles = scene.indices.size() / 3;

    // Screen-space vertices: x, y in pixels, z = depth, w = clip w.
    struct Projected {
        glm::dvec4 screen[3];
    };
    std::vector<Projected> projected(triangles);
    for (size_t t = 0; t < triangles; ++t) {
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 p(scene.vertices[scene.indices[3 * t + k]].position);
            const glm::dvec4 clip = view_projection * glm::dvec4(p, 1.0);
            if (!(clip.w > 0.0)) {
                throw std::runtime_error("raster reference: triangle " + std::to_string(t) +
                                         " has a vertex behind the eye (no clipping here)");
            }
            projected[t].screen[k] = {(clip.x / clip.w * 0.5 + 0.5) * width, (clip.y / clip.w * 0.5 + 0.5) * height,
                                      clip.z / clip.w, clip.w};
        }
    }

    for (uint32_t py = 0; py < height; ++py) {
        for (uint32_t px = 0; px < width; ++px) {
            GbufferTexel& texel = out[size_t(py) * width + px];
            const double cx = px + 0.5, cy = py + 0.5;
            // Fragments at this pixel centre, nearest first.
            struct Fragment {
                double depth;
                size_t triangle;
                double b[3];  // perspective-correct barycentrics
            };
            std::vector<Fragment> fragments;
            for (size_t t = 0; t < triangles; ++t) {
                const glm::dvec4* s = projected[t].screen;
                const double area = (s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[2].x - s[0].x) * (s[1].y - s[0].y);
                if (area == 0.0) continue;
                double w[3];
                bool inside = true;
                for (int i = 0; i < 3; ++i) {
                    const glm::dvec4& a = s[(i + 1) % 3];
                    const glm::dvec4& b = s[(i + 2) % 3];
                    const double e = (b.x - a.x) * (cy - a.y) - (cx - a.x) * (b.y - a.y);
                    const double distance = std::abs(e) / std::hypot(b.x - a.x, b.y - a.y);
                    if (distance < tolerances.edge) texel.ambiguous = true;
                    w[i] = e / area;
                    inside = inside && w[i] >= 0.0;
                }
                if (!inside) continue;
                Fragment f;
                f.triangle = t;
                f.depth = w[0] * s[0].z + w[1] * s[1].z + w[2] * s[2].z;  // depth is linear on screen
                const double sum = w[0] / s[0].w + w[1] / s[1].w + w[2] / s[2].w;
                for (int i = 0; i < 3; ++i) f.b[i] = (w[i] / s[i].w) / sum;
                if (f.depth < 0.0 || f.depth > 1.0) continue;  // outside the depth range
                fragments.push_back(f);
            }
            std::sort(fragments.begin(), fragments.end(),
                      [](const Fragment& a, const Fragment& b) { return a.depth < b.depth; });

            for (const Fragment& f : fragments) {
                const scene::Material& m = scene.materials.at(scene.triangle_materials.at(f.triangle));
                const scene::Vertex* v[3];
                for (int k = 0; k < 3; ++k) v[k] = &scene.vertices[scene.indices[3 * f.triangle + k]];
                glm::dvec3 position(0.0), normal(0.0);
                glm::dvec4 tangent(0.0);
                glm::dvec2 uv(0.0);
                for (int k = 0; k < 3; ++k) {
                    position += f.b[k] * glm::dvec3(v[k]->position);
                    normal += f.b[k] * glm::dvec3(v[k]->normal);
                    tangent += f.b[k] * glm::dvec4(v[k]->tangent);
                    uv += f.b[k] * glm::dvec2(v[k]->uv0);
                }

                const TextureRead base =
                    read_texture(scene, m.base_color_texture, uv, true, glm::dvec4(1.0), tolerances.texel);
                const glm::dvec4 base_color = glm::dvec4(m.base_color_factor) * base.value;
                bool ambiguous = base.ambiguous;
                if (m.alpha_mode != scene::AlphaMode::opaque) {
                    const double cutoff = m.alpha_mode == scene::AlphaMode::blend ? 0.5 : m.alpha_cutoff;
                    if (base_color.a < cutoff) {
                        texel.ambiguous = texel.ambiguous || ambiguous;
                        continue;  // discarded: the next fragment behind it shows
                    }
                }
                const TextureRead mr =
                    read_texture(scene, m.metallic_roughness_texture, uv, false, glm::dvec4(1.0), tolerances.texel);
                const TextureRead nt =
                    read_texture(scene, m.normal_texture, uv, false, glm::dvec4(0.5, 0.5, 1.0, 1.0), tolerances.texel);
                const TextureRead em =
                    read_texture(scene, m.emissive_texture, uv, true, glm::dvec4(0.0), tolerances.texel);
                ambiguous = ambiguous || mr.ambiguous || nt.ambiguous || em.ambiguous;

                const glm::dvec3 p0(v[0]->position), p1(v[1]->position), p2(v[2]->position);
                glm::dvec3 ng = glm::normalize(glm::cross(p1 - p0, p2 - p0));
                glm::dvec3 n = glm::normalize(normal);
                if (glm::dot(ng, viewer - position) < 0.0) ng = -ng;
                const double side = glm::dot(n, ng) < 0.0 ? -1.0 : 1.0;
                if (m.normal_texture != scene::kNoTexture) {
                    glm::dvec3 t = glm::dvec3(tangent) - n * glm::dot(n, glm::dvec3(tangent));
                    if (glm::dot(t, t) > 1e-12) {
                        t = glm::normalize(t);
                        const glm::dvec3 b = (tangent.w < 0.0 ? -1.0 : 1.0) * glm::cross(n, t);
                        const glm::dvec3 tn =
                            (glm::dvec3(nt.value) * 2.0 - 1.0) * glm::dvec3(m.normal_scale, m.normal_scale, 1.0);
                        n = glm::normalize(t * tn.x + b * tn.y + n * tn.z);
                    }
                }

                texel.covered = true;
                texel.ambiguous = texel.ambiguous || ambiguous;
                texel.triangle = int(f.triangle);
                texel.depth = f.depth;
                texel.position = position;
                texel.normal = n * side;
                texel.geometric_normal = ng;
                texel.albedo = glm::dvec3(base_color);
                texel.roughness = m.roughness_factor * mr.value.g;
                texel.metallic = m.metallic_factor * mr.value.b;
                texel.emission = glm::dvec3(m.emission()) * glm::dvec3(em.value);
                break;
            }
        }
    }
    return out;
}

}  // namespace vplkit::reference
