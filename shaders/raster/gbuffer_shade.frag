#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer pass, fragment stage: evaluates the draw's material and writes the G-buffer images
// as shaders/include/vplkit/gbuffer.glsl defines them (position w = 1 and albedo a = 1 mark a
// drawn surface; the host clears position, normals, albedo and emission to 0, depth to 1).

#define VPLKIT_SCENE_MATERIALS_BINDING 2
#define VPLKIT_SCENE_TEXTURES_BINDING 3
#include "vplkit/raster_material.glsl"

layout(push_constant) uniform GbufferPush {
    mat4 view_projection;
    vec3 viewer_position;
    uint material;
} push;

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec4 world_tangent;
layout(location = 3) in vec2 uv0;
layout(location = 4) flat in vec3 face_normal;
layout(location = 5) in vec4 vertex_color;
layout(location = 6) in vec2 uv1;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_geometric_normal;
layout(location = 3) out vec4 out_albedo;
layout(location = 4) out vec4 out_emission;

void main() {
    RasterSurface s = raster_surface(scene_materials.items[push.material], vertex_color, world_normal, world_tangent, uv0, uv1, face_normal,
                                     push.viewer_position - world_position);
    out_position = vec4(world_position, 1.0);
    out_normal = vec4(s.normal, s.roughness);
    out_geometric_normal = vec4(s.geometric_normal, s.metallic);
    out_albedo = vec4(s.albedo, 1.0);
    out_emission = vec4(s.emission, 0.0);
}
