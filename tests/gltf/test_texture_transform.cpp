// KHR_texture_transform, the texture coordinate set a texture names (TEXCOORD_1 included) and
// the sampler's wrap mode, from the loader through the G-buffer's albedo.
//
// Expectation: feature_files' textured_quad (texels red, green, blue, white; nearest filtering).
// At each drawn pixel the test takes the world position the G-buffer stored, forms the file's UV
// (x, 1 - y), applies the extension's matrix as its specification writes it
// (T(offset) R(rotation) S(scale), R = [cos sin; -sin cos]) and the wrap mode as Vulkan defines
// it, and expects that texel's colour. Pixels whose u' lies within 0.02 texel of a texel border
// are skipped (nearest filtering there depends on rounding). The texels are 0 or 1 in sRGB and
// linear, so the tolerance is RGBA16F's: 1e-3.

#include "feature_files.hpp"
#include "gbuffer_readback.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

using gltf_features::TexturedQuad;

constexpr int kRepeat = 10497, kClamp = 33071, kMirror = 33648;

double wrap(double u, int mode) {
    if (mode == kRepeat) return u - std::floor(u);
    if (mode == kMirror) {
        const double f = u - std::floor(u);
        return int(std::floor(u)) % 2 == 0 ? f : 1.0 - f;
    }
    // Clamped: past an edge the edge texel (its centre, so no border skips the pixel).
    return u < 0.0 ? 0.125 : u > 1.0 ? 0.875 : u;
}

// Renders `o`'s quad and compares every drawn pixel away from texel borders with the texel the
// transform picks; returns how many pixels were compared.
uint32_t check_texels(const TexturedQuad& o) {
    scene_test::TempDir dir("texture_transform");
    const auto scene = vplkit::scene::load_gltf(gltf_features::textured_quad(o).write(dir.path(), "quad", true));
    CHECK(vplkit::scene::warning_lines(scene.warnings).empty());
    const auto g = gltf_features::read_gbuffer(scene, 32, 32);
    const double ox = o.transform ? o.offset[0] : 0.0, r = o.transform ? o.rotation : 0.0;
    const double sx = o.transform ? o.scale[0] : 1.0, sy = o.transform ? o.scale[1] : 1.0;
    uint32_t compared = 0;
    double worst = 0.0;
    for (size_t i = 0; i < g.position.size(); ++i) {
        if (g.position[i].w != 1.0f) continue;
        const double u = g.position[i].x, v = 1.0 - g.position[i].y;
        const double u_t = ox + std::cos(r) * sx * u + std::sin(r) * sy * v;
        const double texel_u = 4.0 * wrap(u_t, o.wrap_s);
        if (std::abs(texel_u - std::round(texel_u)) < 0.08) continue;
        const int texel = std::clamp(int(std::floor(texel_u)), 0, 3);
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, double(std::abs(g.albedo[i][c] - gltf_features::kStripTexels[texel][c])));
        }
        ++compared;
    }
    CHECK(worst <= 1e-3);
    return compared;
}

}  // namespace

TEST_CASE("gltf: without a transform the texture reads TEXCOORD_0, or TEXCOORD_1 when the texture names it") {
    TexturedQuad o;
    CHECK(check_texels(o) > 200);
    o.info_tex_coord = 1;  // TEXCOORD_0 is constant: reading it would show white everywhere
    CHECK(check_texels(o) > 200);
}

TEST_CASE("gltf: KHR_texture_transform moves the sampled texel (rotation, offset, scale, texCoord override)") {
    TexturedQuad rotated;  // u' = v: the texel follows y, not x
    rotated.transform = true;
    rotated.rotation = 1.5707963f;
    rotated.offset[1] = 1.0f;
    CHECK(check_texels(rotated) > 200);

    TexturedQuad shifted;  // u' = x + 0.25 from TEXCOORD_1, named by the extension alone
    shifted.transform = true;
    shifted.offset[0] = 0.25f;
    shifted.transform_tex_coord = 1;
    CHECK(check_texels(shifted) > 200);
}

TEST_CASE("gltf: the sampler's wrap mode decides the texels past the edge (repeat, mirrored repeat, clamp)") {
    for (int mode : {kRepeat, kMirror, kClamp}) {
        CAPTURE(mode);
        TexturedQuad o;  // u' = 2x: the right half of the quad reads u' in [1, 2]
        o.transform = true;
        o.scale[0] = 2.0f;
        o.wrap_s = mode;
        CHECK(check_texels(o) > 200);
    }
}

TEST_CASE("gltf: a texture transform reaches the loaded material (KHR_texture_transform's matrix)") {
    TexturedQuad o;
    o.transform = true;
    o.offset[0] = 0.5f;
    o.rotation = 0.3f;
    o.scale[0] = 2.0f;
    o.scale[1] = 3.0f;
    o.transform_tex_coord = 1;
    scene_test::TempDir dir("uv_transform");
    const auto scene = vplkit::scene::load_gltf(gltf_features::textured_quad(o).write(dir.path(), "quad", true));
    const auto& t = scene.materials.at(0).base_color_uv;
    CHECK(t.tex_coord == 1);
    // (u, v) = (1, 1): u' = 0.5 + cos(0.3) 2 + sin(0.3) 3, v' = -sin(0.3) 2 + cos(0.3) 3.
    const glm::vec2 p = t.apply({1.0f, 1.0f});
    CHECK(std::abs(p.x - (0.5 + 2 * std::cos(0.3) + 3 * std::sin(0.3))) < 1e-5);
    CHECK(std::abs(p.y - (-2 * std::sin(0.3) + 3 * std::cos(0.3))) < 1e-5);
}

TEST_CASE("gltf: a texture reading a coordinate set the primitive lacks is one warning") {
    TexturedQuad o;
    o.info_tex_coord = 1;
    auto b = gltf_features::textured_quad(o);
    std::string& mesh = b.meshes.at(0);
    const size_t at = mesh.find(",\"TEXCOORD_1\"");
    REQUIRE(at != std::string::npos);
    mesh.erase(at, mesh.find('}', at) - at);  // TEXCOORD_1 is the last attribute
    scene_test::TempDir dir("missing_set");
    const auto scene = vplkit::scene::load_gltf(b.write(dir.path(), "quad", true));
    const auto lines = vplkit::scene::warning_lines(scene.warnings);
    REQUIRE(lines.size() == 1);
    CHECK(lines[0].find("read TEXCOORD_1, which the primitive lacks") != std::string::npos);
}
