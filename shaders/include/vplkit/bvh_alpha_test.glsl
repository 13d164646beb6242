#ifndef VPLKIT_BVH_ALPHA_TEST_GLSL
#define VPLKIT_BVH_ALPHA_TEST_GLSL

// The alpha test of bvh.glsl's traversal: whether a hit on an alpha-tested triangle is on the
// surface. Included by vplkit/bvh.glsl (after BvhTriangle and bvh_alpha_word), not on its own.
//
// Alpha-tested triangles (glTF MASK materials, and BLEND ones, which the G-buffer draws where
// alpha >= 0.5): a ray passes through a triangle where alpha = base colour factor alpha x COLOR_0
// alpha x base colour texture alpha < cutoff, exactly where the G-buffer discards, so shadow
// rays, light paths and VPL visibility see the surface the camera sees. A triangle's `alpha` is
// 0 when it is opaque (the test is skipped: a triangle hit in an opaque scene costs one compare
// of a word already loaded); else the offset of its record in `bvh_alpha` (a plain uint array,
// written by vplkit::add_alpha_tests, runtime/include/vplkit/bvh_alpha.hpp; words 0-11 hold no
// record but the header above):
//   triangle record (10 words): the base colour texture's UVs at v0, v1, v2 (texture transform
//     and texCoord set applied; 6 floats), alpha factor x COLOR_0 alpha at v0, v1, v2 (3 floats),
//     the offset of its material record;
//   material record (5 words): cutoff (float), texture width, height (0 x 0: no texture, alpha
//     1), wrap modes (S in bits 0-1, T in bits 2-3: 0 repeat, 1 clamp, 2 mirrored) and the
//     magnification filter (bit 4: nearest), the offset of the texture's alpha bytes (width x
//     height, rows top to bottom, 4 to a word).
// Why a plain array and not a sampler: lavapipe has no descriptor indexing, so compute shaders
// cannot pick one of many textures per hit; the alpha channels of the masked materials' base
// colour textures are few (Sponza: its plants and chains) and a byte per texel. The texture is
// read at level 0 with the sampler's wrap modes and magnification filter, nearest or bilinear
// (the G-buffer's minification and mip filtering differ only where the footprint spans several
// texels: at the mask's edges, far away).

#ifndef VPLKIT_BVH_GLSL
#error "vplkit/bvh_alpha_test.glsl is included by vplkit/bvh.glsl"
#endif

const uint kBvhAlphaNearest = 16u;  // material record word 3: the texture's magFilter is NEAREST

// Texel coordinates beyond this many texels from the origin are clamped to it before wrapping
// (2^21: a float UV that far out resolves no better than about a texel anyway).
const int kBvhAlphaMaxTexel = 2097152;

// Texel coordinate i wrapped into [0, n) by glTF's wrap mode (0 repeat, 1 clamp to edge, 2
// mirrored repeat). Branch-free and without integer division, which lavapipe runs lane by lane
// (a scalar divide per lane, where everything else here is one SIMD instruction): the quotient
// floor(i / period) is taken in float. Float division is accurate to 2.5 ulp (Vulkan), so for
// |i| <= 2^21 the quotient is off by at most 1 and one correction either way makes r exact.
int bvh_alpha_wrap(int i, int n, uint mode) {
    i = clamp(i, -kBvhAlphaMaxTexel, kBvhAlphaMaxTexel);
    int period = mode == 2u ? 2 * n : n;
    int r = i - period * int(floor(float(i) / float(period)));
    r += r < 0 ? period : 0;
    r -= r >= period ? period : 0;
    int mirrored = r < n ? r : period - 1 - r;
    return mode == 1u ? clamp(i, 0, n - 1) : (mode == 2u ? mirrored : r);
}

// One texel of an alpha record's texture (bytes 4 to a word, rows of `width`), at wrapped
// coordinates.
float bvh_alpha_texel(uint data, uint width, int x, int y) {
    uint index = uint(y) * width + uint(x);
    return float((bvh_alpha_word(data + index / 4u) >> (8u * (index % 4u))) & 0xffu) / 255.0;
}

// Whether the alpha-test code is compiled in (specialization constant kBvhAlphaTest, id
// kBvhAlphaTestConstantId; stages::bvh_spec sets it from BvhBuffers::alpha_tests). Not a runtime
// branch: lavapipe runs a divergent branch under a lane mask whether or not a lane takes it, and
// the alpha code in the triangle loop made every shadow ray 3.7x slower in an opaque scene (exact
// GI, in-repo Cornell box, 128 x 128, 256 paths: 1.48 s -> 5.5 s), even behind a uniform flag
// read from bvh_alpha. Compiled out, an opaque scene's traversal is what it was before alpha tests.
layout(constant_id = 20) const uint kBvhAlphaTest = 1u;

bool bvh_has_alpha_tests() {
    return kBvhAlphaTest != 0u;
}

// Whether the hit at `barycentrics` on `tri` is on the surface (its alpha test passes).
bool bvh_alpha_passes(BvhTriangle tri, vec2 barycentrics) {
    if (tri.alpha == 0u) {
        return true;
    }
    uint r = tri.alpha;
    vec3 w = vec3(1.0 - barycentrics.x - barycentrics.y, barycentrics.x, barycentrics.y);
    float alpha = w.x * uintBitsToFloat(bvh_alpha_word(r + 6u)) + w.y * uintBitsToFloat(bvh_alpha_word(r + 7u)) +
                  w.z * uintBitsToFloat(bvh_alpha_word(r + 8u));
    uint m = bvh_alpha_word(r + 9u);
    float cutoff = uintBitsToFloat(bvh_alpha_word(m));
    uvec2 size = uvec2(bvh_alpha_word(m + 1u), bvh_alpha_word(m + 2u));
    if (size.x > 0u && size.y > 0u) {
        vec2 uv = w.x * vec2(uintBitsToFloat(bvh_alpha_word(r)), uintBitsToFloat(bvh_alpha_word(r + 1u))) +
                  w.y * vec2(uintBitsToFloat(bvh_alpha_word(r + 2u)), uintBitsToFloat(bvh_alpha_word(r + 3u))) +
                  w.z * vec2(uintBitsToFloat(bvh_alpha_word(r + 4u)), uintBitsToFloat(bvh_alpha_word(r + 5u)));
        uint wrap = bvh_alpha_word(m + 3u);
        uint data = bvh_alpha_word(m + 4u);
        // Bilinear between texel centres at (i + 0.5) / size (Vulkan's convention); nearest is the
        // same code with the texel under uv at weight 1 (mix(a, b, 0.0) is a exactly), so that
        // the two filters are not two branches that lavapipe would both run.
        bool nearest = (wrap & kBvhAlphaNearest) != 0u;
        vec2 x = uv * vec2(size) - (nearest ? vec2(0.0) : vec2(0.5));
        vec2 base = clamp(floor(x), vec2(-float(kBvhAlphaMaxTexel)), vec2(float(kBvhAlphaMaxTexel)));
        vec2 f = nearest ? vec2(0.0) : fract(x);
        ivec2 i0 = ivec2(base);
        ivec2 n = ivec2(size);
        int x0 = bvh_alpha_wrap(i0.x, n.x, wrap & 3u);
        int x1 = bvh_alpha_wrap(i0.x + 1, n.x, wrap & 3u);
        int y0 = bvh_alpha_wrap(i0.y, n.y, (wrap >> 2) & 3u);
        int y1 = bvh_alpha_wrap(i0.y + 1, n.y, (wrap >> 2) & 3u);
        float a00 = bvh_alpha_texel(data, size.x, x0, y0);
        float a10 = bvh_alpha_texel(data, size.x, x1, y0);
        float a01 = bvh_alpha_texel(data, size.x, x0, y1);
        float a11 = bvh_alpha_texel(data, size.x, x1, y1);
        alpha *= mix(mix(a00, a10, f.x), mix(a01, a11, f.x), f.y);
    }
    return alpha >= cutoff;
}

#endif
