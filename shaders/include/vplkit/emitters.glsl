#ifndef VPLKIT_EMITTERS_GLSL
#define VPLKIT_EMITTERS_GLSL

// Emissive triangles as area lights. Each emits radiance `radiance` from its front side (the
// side its counter-clockwise winding faces), uniformly: glTF's emissive factor x strength (the
// emissive texture is not sampled here: its mean would be needed for power, and the kit's scenes
// light with constant emitters).
struct EmissiveTriangle {
    vec3 v0;
    float area;
    vec3 v1;
    float pmf;       // probability of choosing this triangle: its power / the total power
    vec3 v2;
    float cdf;       // sum of the pmfs up to and including this one (the last is 1)
    vec3 radiance;   // W / (m^2 sr), linear RGB
};

#endif
