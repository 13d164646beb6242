#ifndef VPLKIT_EMITTERS_GLSL
#define VPLKIT_EMITTERS_GLSL

// Emissive triangles as area lights. Each emits radiance `radiance` from its front side (the
// side its counter-clockwise winding faces), and from its back too when double-sided (glTF's
// doubleSided), uniformly: glTF's emissive factor x strength x the emissive texture's mean over
// the triangle (vplkit/gpu_lights.hpp: triangle_emission; the texture's variation within a
// triangle is not kept).
struct EmissiveTriangle {
    vec3 v0;
    float area;
    vec3 v1;
    uint double_sided;  // 1: emits from both sides
    vec3 v2;
    // The selection CDF (stages/selection_cdf.hpp): multiples of 2^-24, the last is 1; this
    // triangle is chosen with probability cdf - the previous triangle's cdf (its pmf).
    float cdf;
    vec3 radiance;      // W / (m^2 sr), linear RGB
};

#endif
