#ifndef VPLKIT_GBUFFER_GLSL
#define VPLKIT_GBUFFER_GLSL

// The G-buffer every screen-space stage reads (written by the G-buffer raster pass; host side:
// stages/include/vplkit/stages/gbuffer_views.hpp). All images have the output's size.
//   position          RGBA32F  xyz world position, moved toward the viewer by about 2^-16 of its
//                              coordinates (gbuffer_shade.frag: so rays can start there, also at
//                              concave edges); w = 1 where a surface was drawn, 0 background
//   normal            RGBA32F  xyz unit shading normal (normal map applied), on the viewer's side
//                              of the surface; w = perceptual roughness (glTF roughness);
//                              negative: the pure Lambertian BRDF, albedo / pi (brdf.glsl)
//   geometric_normal  RGBA32F  xyz unit face normal, on the same side as `normal` (ray origins
//                              are offset along it); w = metallic
//   albedo            RGBA16F  rgb linear base colour (factor x texture); a = 1
//   emission          RGBA16F  rgb emitted radiance (factor x strength x texture); a = 0
//   depth             D32      the raster depth (1 = far plane, cleared)
//   motion            RGBA32F  xyz the point's position in the previous frame's pose less its
//                              position now (world space: a camera move is not in it); exactly 0
//                              where nothing moved; w = 0. Read by temporal accumulation only

struct GbufferSample {
    vec3 position;
    bool covered;
    vec3 normal;
    float roughness;
    vec3 geometric_normal;
    float metallic;
    vec3 albedo;
    vec3 emission;
};

GbufferSample gbuffer_decode(vec4 position, vec4 normal, vec4 geometric_normal, vec4 albedo, vec4 emission) {
    GbufferSample s;
    s.position = position.xyz;
    s.covered = position.w > 0.5;
    s.normal = normal.xyz;
    s.roughness = normal.w;
    s.geometric_normal = geometric_normal.xyz;
    s.metallic = geometric_normal.w;
    s.albedo = albedo.rgb;
    s.emission = emission.rgb;
    return s;
}

#endif
