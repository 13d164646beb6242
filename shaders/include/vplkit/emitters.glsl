#ifndef VPLKIT_EMITTERS_GLSL
#define VPLKIT_EMITTERS_GLSL

// Emissive triangles as area lights. Each emits radiance `radiance` from its front side (the
// side its counter-clockwise winding faces), and from its back too when double-sided (glTF's
// doubleSided), uniformly: glTF's emissive factor x strength (the emissive texture is not
// sampled here: its mean would be needed for power, and the kit's scenes light with constant
// emitters).
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
