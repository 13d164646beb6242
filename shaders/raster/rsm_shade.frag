#version 460
#extension GL_GOOGLE_include_directive : require
// Shadow map + reflective shadow map pass, fragment stage. One texel of a reflective shadow map
// (Dachsbacher and Stamminger 2005, "Reflective Shadow Maps"; the thesis section 2.2 and 4.1
// generate VPLs from these texels) is a small surface patch lit by the light: its world
// position, its normal, and the flux it reflects. The depth attachment of the
// same pass is the light's shadow map. Images: runtime/include/vplkit/stages/shadow_maps.hpp.

#define VPLKIT_SCENE_MATERIALS_BINDING 2
#define VPLKIT_SCENE_TEXTURES_BINDING 3
#include "vplkit/lights.glsl"
#include "vplkit/raster_material.glsl"

// rsm_raster.vert's block (one push range for both stages); the addresses are its alone.
layout(push_constant) uniform RsmPush {
    mat4 view_projection;
    vec2 face_origin;
    uint material;
    uvec2 scene_vertex_address;
    uvec2 scene_index_address;
    uint scene_vertex_count;
    uint scene_index_count;
} push;

layout(std140, set = 0, binding = 7) uniform RsmLight {
    vec3 intensity;  // colour x intensity: irradiance W/m^2 (directional) or intensity W/sr
    uint type;       // kLight* (vplkit/lights.glsl; scene::LightType order)
    vec3 position;   // point and spot
    float range;     // point and spot; 0 = unlimited
    vec3 direction;  // unit, the direction the light travels (directional and spot)
    float texel_area;      // directional: cross-section of one texel's beam, m^2
    float tan_half_fov;    // point and spot: a face spans [-tan_half_fov, tan_half_fov]^2 at distance 1
    float face_texels;     // point and spot: texels along a face's side
    float spot_scale;      // spot falloff, as PunctualLight's
    float spot_offset;
} light;

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec4 world_tangent;
layout(location = 3) in vec2 uv0;
layout(location = 4) flat in vec3 face_normal;
layout(location = 5) in vec4 vertex_color;
layout(location = 6) in vec2 uv1;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_flux;

// atan(y / x) for y >= 0, x > 0. Vulkan lets atan be off by 4096 ulp (5e-4 relative; lavapipe:
// 2e-5, a bias that adds up over a map's texels), so the small arguments of texel-sized
// triangles take the series, whose first omitted term z^9 / 9 is below 1e-9 for z < 0.1.
float accurate_atan(float y, float x) {
    float z = y / x;
    if (z < 0.1) {
        float z2 = z * z;
        return z * (1.0 - z2 * (1.0 / 3.0 - z2 * (1.0 / 5.0 - z2 * (1.0 / 7.0))));
    }
    return atan(y, x);
}

// Solid angle of the triangle (a, b, c) seen from the origin, given the triple product
// a . (b x c) (Van Oosterom and Strackee 1983, "The solid angle of a plane triangle"; the
// denominator is positive for the triangles of a face, which span less than a hemisphere).
float triangle_solid_angle(vec3 a, vec3 b, vec3 c, float triple) {
    float la = length(a);
    float lb = length(b);
    float lc = length(c);
    return 2.0 * accurate_atan(triple, la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la);
}

// Exact solid angle of the rectangle [lo, hi] on the plane z = 1, as the triangles (a, b, c) and
// (a, c, d). Both triple products equal (hi - lo).x * (hi - lo).y exactly (expand
// a . ((b - a) x (c - a))), so no difference of nearly equal numbers is formed even for the tiny
// texels of a 2048^2 face.
float rect_solid_angle(vec2 lo, vec2 hi) {
    vec3 a = vec3(lo.x, lo.y, 1.0);
    vec3 b = vec3(hi.x, lo.y, 1.0);
    vec3 c = vec3(hi.x, hi.y, 1.0);
    vec3 d = vec3(lo.x, hi.y, 1.0);
    float triple = (hi.x - lo.x) * (hi.y - lo.y);
    return triangle_solid_angle(a, b, c, triple) + triangle_solid_angle(a, c, d, triple);
}

// Power the light sends into this texel's beam; all of it lands on the surface patch the texel
// sees (the first surface along the beam).
//   directional: irradiance E on a plane facing the light times the beam's cross-section A; the
//     patch has area A / cos(theta) and receives E cos(theta), so the cosines cancel: E A.
//   point, spot: intensity I (W/sr) times the texel's solid angle omega, times the spot falloff
//     and the range window of KHR_lights_punctual at the patch (taken at the surface point of
//     the texel's centre), exactly as vplkit/lights.glsl applies them to direct light.
// The reflected flux is the diffuse reflectance x that (Dachsbacher and Stamminger 2005: a
// texel's flux is the light's flux through it times the surface's reflectivity): summed over the
// texels it is the power the surfaces the light reaches reflect diffusely, which the tests check
// on planes against the analytic value. Diffuse reflectance = base colour x (1 - metallic), as
// instant radiosity's VPLs use it (stages/vpl_tracing.hpp): a VPL re-emits diffusely, and a
// metal reflects its light specularly, which no VPL carries.
vec3 texel_incident_power() {
    if (light.type == kLightDirectional) {
        return light.intensity * light.texel_area;
    }
    // The texel's square on the face's plane at distance 1 (the sign convention of the axes does
    // not change a rectangle's solid angle).
    vec2 texel = floor(gl_FragCoord.xy - push.face_origin);
    float step = 2.0 * light.tan_half_fov / light.face_texels;
    vec2 lo = texel * step - light.tan_half_fov;
    float omega = rect_solid_angle(lo, lo + step);

    // The light's falloff (range window, spot cone) as the direct-light stage applies it
    // (vplkit/lights.glsl): its irradiance at the patch is I x falloff / d^2.
    PunctualLight l = PunctualLight(light.position, light.type, light.direction, light.range, light.intensity,
                                    light.spot_scale, light.spot_offset);
    LightIncidence incidence = light_incidence(l, world_position);
    return incidence.irradiance * (incidence.distance * incidence.distance * omega);
}

void main() {
    vec3 to_light = light.type == kLightDirectional ? -light.direction : light.position - world_position;
    RasterSurface s = raster_surface(scene_materials.items[push.material], vertex_color, world_normal, world_tangent, uv0, uv1, face_normal,
                                     to_light);
    out_position = vec4(world_position, 1.0);
    out_normal = vec4(s.normal, 0.0);
    out_flux = vec4(s.albedo * (1.0 - s.metallic) * texel_incident_power(), 0.0);
}
