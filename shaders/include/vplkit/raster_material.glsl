#ifndef VPLKIT_RASTER_MATERIAL_GLSL
#define VPLKIT_RASTER_MATERIAL_GLSL

// glTF metallic-roughness materials as GpuScene uploads them, evaluated at a rasterized
// fragment: base colour, alpha test, normal mapping, the facing of the normals. Shared by the
// G-buffer and the reflective-shadow-map fragment shaders so that both see the same surface.
//
// Including it (fragment shaders): define the binding of the material buffer and the first of
// four consecutive texture bindings,
//     #define VPLKIT_SCENE_MATERIALS_BINDING 2
//     #define VPLKIT_SCENE_TEXTURES_BINDING 3   // base colour, metallic-roughness, normal, emissive
//     #include "vplkit/raster_material.glsl"
//
// lavapipe has no descriptor indexing, so a draw binds its one material's four textures as
// combined image samplers (push descriptors); a material without a texture binds a 1x1 default
// (white, white, flat normal, black). Colour textures are sampled through sRGB views, data
// textures through UNORM views, so every value read here is linear.

#if !defined(VPLKIT_SCENE_MATERIALS_BINDING) || !defined(VPLKIT_SCENE_TEXTURES_BINDING)
#error "define VPLKIT_SCENE_MATERIALS_BINDING and VPLKIT_SCENE_TEXTURES_BINDING before including vplkit/raster_material.glsl"
#endif

const uint kSceneMaterialAlphaTest = 1u;      // discard below alpha_cutoff (glTF MASK, and BLEND at 0.5)
const uint kSceneMaterialNormalTexture = 2u;  // has a normal texture (the default one is never read)
const uint kSceneMaterialDoubleSided = 4u;    // recorded; both sides are drawn and shaded alike anyway

struct SceneMaterial {
    vec4 base_color_factor;  // linear RGBA
    vec3 emission;           // emissive factor x emissive strength, linear RGB
    float alpha_cutoff;
    float metallic_factor;
    float roughness_factor;
    float normal_scale;
    uint flags;  // kSceneMaterial* bits
    // Per texture (base colour, metallic-roughness, normal, emissive) the rows of its 2x3 UV
    // transform (KHR_texture_transform; identity without one): u' = dot(u_row.xyz, (uv, 1)),
    // v' = dot(v_row.xyz, (uv, 1)); u_row.w = its texture coordinate set (0 or 1).
    vec4 base_color_u_row;
    vec4 base_color_v_row;
    vec4 metallic_roughness_u_row;
    vec4 metallic_roughness_v_row;
    vec4 normal_u_row;
    vec4 normal_v_row;
    vec4 emissive_u_row;
    vec4 emissive_v_row;
};

layout(std430, set = 0, binding = VPLKIT_SCENE_MATERIALS_BINDING) readonly buffer SceneMaterialBuffer {
    SceneMaterial items[];
} scene_materials;

layout(set = 0, binding = VPLKIT_SCENE_TEXTURES_BINDING) uniform sampler2D base_color_texture;              // sRGB view
layout(set = 0, binding = VPLKIT_SCENE_TEXTURES_BINDING + 1) uniform sampler2D metallic_roughness_texture;  // UNORM: G roughness, B metallic
layout(set = 0, binding = VPLKIT_SCENE_TEXTURES_BINDING + 2) uniform sampler2D normal_texture;              // UNORM, tangent space
layout(set = 0, binding = VPLKIT_SCENE_TEXTURES_BINDING + 3) uniform sampler2D emissive_texture;            // sRGB view

struct RasterSurface {
    vec3 albedo;            // base colour factor x texture x vertex colour
    vec3 normal;            // unit shading normal (normal map applied) on the viewer's side
    vec3 geometric_normal;  // unit face normal on the viewer's side
    float roughness;        // perceptual (glTF) roughness
    float metallic;
    vec3 emission;          // emitted radiance
};

// The texture coordinates one texture reads: its set, through its transform.
vec2 material_uv(vec4 u_row, vec4 v_row, vec2 uv0, vec2 uv1) {
    vec3 uv = vec3(u_row.w != 0.0 ? uv1 : uv0, 1.0);
    return vec2(dot(u_row.xyz, uv), dot(v_row.xyz, uv));
}

// The material at a fragment with vertex colour `color` (COLOR_0, white without one) and texture
// coordinates uv0, uv1 (TEXCOORD_0, TEXCOORD_1) seen from
// direction `to_viewer` (any length; for the G-buffer the
// camera, for a shadow map the light). Discards the fragment when the alpha test fails.
//
// Facing: every triangle is drawn from both sides (no culling: a G-buffer or RSM for GI must not
// show holes where a single-sided surface is seen from behind). The face normal is turned to the
// viewer's side; the shading normal is computed in the file's tangent frame and then the whole
// frame is turned to the side the vertex normal must be on (glTF 2.0, double-sided materials:
// back-face normals are reversed; applied to single-sided ones too for the reason above).
RasterSurface raster_surface(SceneMaterial m, vec4 color, vec3 vertex_normal, vec4 vertex_tangent, vec2 uv0, vec2 uv1,
                             vec3 face_normal, vec3 to_viewer) {
    // Every texture is sampled before the alpha test may discard, so the implicit derivatives of
    // the quad's surviving invocations stay defined.
    // glTF 2.0 3.9.2: base colour = factor x texture x COLOR_0 (alpha included).
    vec4 base_color = m.base_color_factor *
                      texture(base_color_texture, material_uv(m.base_color_u_row, m.base_color_v_row, uv0, uv1)) * color;
    vec4 metallic_roughness = texture(metallic_roughness_texture,
                                      material_uv(m.metallic_roughness_u_row, m.metallic_roughness_v_row, uv0, uv1));
    vec3 tangent_normal = texture(normal_texture, material_uv(m.normal_u_row, m.normal_v_row, uv0, uv1)).xyz;
    vec3 emissive = texture(emissive_texture, material_uv(m.emissive_u_row, m.emissive_v_row, uv0, uv1)).rgb;
    if ((m.flags & kSceneMaterialAlphaTest) != 0u && base_color.a < m.alpha_cutoff) {
        discard;
    }

    RasterSurface s;
    vec3 n = vertex_normal;
    float n_length2 = dot(n, n);
    vec3 ng = face_normal;
    if (dot(ng, ng) == 0.0) {
        ng = n_length2 > 0.0 ? n * inversesqrt(n_length2) : vec3(0.0, 0.0, 1.0);
    }
    n = n_length2 > 0.0 ? n * inversesqrt(n_length2) : ng;
    if (dot(ng, to_viewer) < 0.0) {
        ng = -ng;
    }
    // The side the vertex normal must be on; the tangent frame turns with it, so the normal
    // map's perturbation keeps its meaning seen from either side.
    float side = dot(n, ng) < 0.0 ? -1.0 : 1.0;
    if ((m.flags & kSceneMaterialNormalTexture) != 0u) {
        // glTF 2.0 normalTexture: scaledNormal = normalize((sample * 2 - 1) * (scale, scale, 1)),
        // in the frame (tangent, bitangent = w * cross(normal, tangent), normal).
        vec3 t = vertex_tangent.xyz - n * dot(n, vertex_tangent.xyz);
        float t_length2 = dot(t, t);
        if (t_length2 > 1e-12) {
            t *= inversesqrt(t_length2);
            vec3 b = (vertex_tangent.w < 0.0 ? -1.0 : 1.0) * cross(n, t);
            vec3 tn = (tangent_normal * 2.0 - 1.0) * vec3(m.normal_scale, m.normal_scale, 1.0);
            vec3 mapped = t * tn.x + b * tn.y + n * tn.z;
            float mapped_length2 = dot(mapped, mapped);
            if (mapped_length2 > 0.0) {
                n = mapped * inversesqrt(mapped_length2);
            }
        }
    }
    s.albedo = base_color.rgb;
    s.normal = n * side;
    s.geometric_normal = ng;
    s.roughness = m.roughness_factor * metallic_roughness.g;
    s.metallic = m.metallic_factor * metallic_roughness.b;
    s.emission = m.emission * emissive;
    return s;
}

#endif
