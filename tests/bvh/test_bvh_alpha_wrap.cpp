// The alpha test's texture read (bvh_alpha_test.glsl's bvh_alpha_passes, bvh_alpha_wrap): glTF's wrap
// modes (repeat, clamp to edge, mirrored repeat) on negative and far texel coordinates of a
// texture whose sides are not powers of two, with nearest and bilinear filtering, against a
// double-precision reference of the same rules (integer floor-modulo, texel centres at i + 0.5).
//
// Expectation: a masked quad in z = 0 whose UVs are an affine map of x, y spanning many periods
// (so both triangles interpolate the same map); a vertical ray at (x, y) is occluded exactly
// where the reference alpha is >= the cutoff 0.5. Rays whose reference is within rounding of the
// answer are skipped: nearest, within 1e-3 texel of a texel border; bilinear, alpha within 1e-3
// of the cutoff (the GPU's float UVs are off by up to ~5e-4 texel, alpha by as much). At most 5% may be skipped.

#include "bvh_test_support.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_alpha.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace {

using vplkit::scene::Filter;
using vplkit::scene::Wrap;

constexpr uint32_t kWidth = 5, kHeight = 3;
// Alpha bytes, row by row: opaque, cut-out and in-between values, so bilinear weights matter.
constexpr uint8_t kAlpha[kHeight][kWidth] = {{255, 0, 160, 255, 0}, {0, 100, 255, 0, 255}, {255, 255, 0, 60, 200}};

// UV at (x, y) on the quad: far from [0, 1] and negative in places.
glm::dvec2 uv_at(double x, double y, double base) {
    return {base - 7.3 + 13.1 * x, -4.6 + 9.7 * y};
}

int wrap(int64_t i, int n, Wrap mode) {
    if (mode == Wrap::clamp_to_edge) return int(std::clamp<int64_t>(i, 0, n - 1));
    if (mode == Wrap::repeat) return int(((i % n) + n) % n);
    const int64_t period = 2 * int64_t(n);
    const int64_t r = ((i % period) + period) % period;
    return int(r < n ? r : period - 1 - r);
}

double texel(int64_t x, int64_t y, Wrap s, Wrap t) {
    return kAlpha[wrap(y, kHeight, t)][wrap(x, kWidth, s)] / 255.0;
}

// The reference alpha at uv, and whether it is within rounding of the cutoff's answer.
struct Reference {
    double alpha = 0.0;
    bool ambiguous = false;
};

Reference reference_alpha(glm::dvec2 uv, Wrap s, Wrap t, Filter filter) {
    Reference r;
    if (filter == Filter::nearest) {
        const glm::dvec2 p = uv * glm::dvec2(kWidth, kHeight);
        const glm::dvec2 f = p - glm::floor(p);
        r.ambiguous = f.x < 1e-3 || f.x > 1.0 - 1e-3 || f.y < 1e-3 || f.y > 1.0 - 1e-3;
        r.alpha = texel(int64_t(std::floor(p.x)), int64_t(std::floor(p.y)), s, t);
        return r;
    }
    const glm::dvec2 p = uv * glm::dvec2(kWidth, kHeight) - 0.5;
    const glm::dvec2 i = glm::floor(p);
    const glm::dvec2 f = p - i;
    const int64_t x = int64_t(i.x), y = int64_t(i.y);
    const double top = texel(x, y, s, t) * (1.0 - f.x) + texel(x + 1, y, s, t) * f.x;
    const double bottom = texel(x, y + 1, s, t) * (1.0 - f.x) + texel(x + 1, y + 1, s, t) * f.x;
    r.alpha = top * (1.0 - f.y) + bottom * f.y;
    r.ambiguous = std::fabs(r.alpha - 0.5) < 1e-3;
    return r;
}

// The unit quad [0, 1]^2 in z = 0, one MASK material (cutoff 0.5) with the texture.
vplkit::scene::Scene quad_scene(Wrap s, Wrap t, Filter filter, double base) {
    vplkit::scene::Scene scene;
    vplkit::scene::Image image;
    image.width = kWidth;
    image.height = kHeight;
    for (uint32_t y = 0; y < kHeight; ++y) {
        for (uint32_t x = 0; x < kWidth; ++x) image.rgba.insert(image.rgba.end(), {255, 255, 255, kAlpha[y][x]});
    }
    scene.images.push_back(image);
    vplkit::scene::Texture texture;
    texture.sampler.wrap_s = s;
    texture.sampler.wrap_t = t;
    texture.sampler.mag_filter = filter;
    scene.textures.push_back(texture);
    vplkit::scene::Material material;
    material.alpha_mode = vplkit::scene::AlphaMode::mask;
    material.alpha_cutoff = 0.5f;
    material.base_color_texture = 0;
    scene.materials.push_back(material);
    const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const glm::vec2& c : corners) {
        vplkit::scene::Vertex v;
        v.position = {c.x, c.y, 0.0f};
        v.normal = {0.0f, 0.0f, 1.0f};
        v.uv0 = glm::vec2(uv_at(c.x, c.y, base));
        scene.vertices.push_back(v);
    }
    scene.indices = {0, 1, 2, 0, 2, 3};
    scene.triangle_materials = {0, 0};
    return scene;
}

}  // namespace

TEST_CASE("bvh alpha: texels are read with glTF's wrap modes and filters, far from [0, 1] and negative") {
    constexpr uint32_t kGrid = 64;
    std::vector<vplkit::shaders::BvhRay> rays;
    for (uint32_t j = 0; j < kGrid; ++j) {
        for (uint32_t i = 0; i < kGrid; ++i) {
            const glm::vec3 origin((i + 0.37f) / kGrid, (j + 0.61f) / kGrid, 1.0f);
            rays.push_back(vplkit::bvh_test::make_ray(origin, {0.0f, 0.0f, -1.0f}, 0.0f, 2.0f));
        }
    }
    const Wrap wraps[3] = {Wrap::repeat, Wrap::clamp_to_edge, Wrap::mirrored_repeat};
    // base: UV offset along u; 300 puts the texel coordinates near 1500 (the GPU's float UVs there
    // are off by up to ~5e-4 texel: within the skip margins).
    for (double base : {0.0, 300.0}) {
        for (Wrap s : wraps) {
            for (Wrap t : wraps) {
                for (Filter filter : {Filter::nearest, Filter::linear}) {
                    CAPTURE(base);
                    CAPTURE(int(s));
                    CAPTURE(int(t));
                    CAPTURE(int(filter));
                    const auto scene = quad_scene(s, t, filter, base);
                    const vplkit::Bvh bvh = vplkit::build_scene_bvh(scene);
                    const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
                    REQUIRE(gpu.alpha_tests);
                    const auto occluded = vplkit::bvh_test::trace_occlusion(gpu, rays);
                    size_t skipped = 0, wrong = 0, blocked = 0;
                    for (size_t r = 0; r < rays.size(); ++r) {
                        const auto& o = rays[r].origin;
                        const Reference ref = reference_alpha(uv_at(o.x, o.y, base), s, t, filter);
                        if (ref.ambiguous) {
                            ++skipped;
                            continue;
                        }
                        const bool expected = ref.alpha >= 0.5;
                        blocked += expected ? 1 : 0;
                        if ((occluded[r] != 0) != expected) {
                            if (++wrong <= 3)
                                MESSAGE("ray at (" << o.x << ", " << o.y << "): reference alpha " << ref.alpha);
                        }
                    }
                    CHECK(wrong == 0);
                    CHECK(double(skipped) <= 0.05 * double(rays.size()));
                    // Both answers occur.
                    CHECK(blocked > rays.size() / 5);
                    CHECK(blocked < rays.size() * 4 / 5);
                }
            }
        }
    }
}
