#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// Shadow map + reflective shadow map pass, vertex stage: the scene seen from one face of a
// light's shadow map (see vplkit/raster_scene.glsl for the non-indexed vertex pulling).

// The same block as rsm_shade.frag's (one push range for both stages).
layout(push_constant) uniform RsmPush {
    mat4 view_projection;  // world -> the face's Vulkan clip space
    vec2 face_origin;      // the face's top-left texel in the atlas (0 for a single-face map)
    uint material;
    // raster_scene.glsl's addresses (read only with kSceneAddressed)
    uvec2 scene_vertex_address;
    uvec2 scene_index_address;
    uint scene_vertex_count;
    uint scene_index_count;
} push;

#define VPLKIT_SCENE_VERTICES_BINDING 0
#define VPLKIT_SCENE_INDICES_BINDING 1
#define VPLKIT_SCENE_PUSH push
#include "vplkit/raster_scene.glsl"

layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 world_normal;
layout(location = 2) out vec4 world_tangent;
layout(location = 3) out vec2 uv0;
layout(location = 4) flat out vec3 face_normal;
layout(location = 5) out vec4 vertex_color;
layout(location = 6) out vec2 uv1;

void main() {
    uint triangle = uint(gl_VertexIndex) / 3u;
    SceneVertex v = scene_triangle_vertex(triangle, uint(gl_VertexIndex) % 3u);
    world_position = v.position;
    world_normal = v.normal;
    world_tangent = v.tangent;
    uv0 = v.uv0;
    uv1 = v.uv1;
    vertex_color = v.color;
    face_normal = scene_face_normal(triangle);
    gl_Position = push.view_projection * vec4(v.position, 1.0);
}
