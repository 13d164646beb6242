#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// G-buffer pass, vertex stage: pulls its triangle's vertex (non-indexed draw, see
// vplkit/raster_scene.glsl) and passes world-space attributes and the exact face normal on.

// The same block as gbuffer_shade.frag's (one push range for both stages).
layout(push_constant) uniform GbufferPush {
    mat4 view_projection;  // world -> Vulkan clip space (y down, depth 0 near .. 1 far)
    vec3 viewer_position;  // the camera's world position
    uint material;         // index into the material buffer (one per draw)
    uint has_motion;       // 1: previous_vertices holds the previous frame's pose
    // raster_scene.glsl's addresses (read only with kSceneAddressed), and the previous pose's
    uvec2 scene_vertex_address;
    uvec2 scene_index_address;
    uint scene_vertex_count;
    uint scene_index_count;
    uvec2 previous_vertex_address;
} push;

#define VPLKIT_SCENE_VERTICES_BINDING 0
#define VPLKIT_SCENE_INDICES_BINDING 1
#define VPLKIT_SCENE_PUSH push
#include "vplkit/raster_scene.glsl"

// The pose the previous frame was drawn with (scene::Vertex[], the same triangles), read only
// when push.has_motion is 1; a still scene binds its current vertices here, never read, because
// a descriptor set must have every binding filled (with kSceneAddressed it is read at
// push.previous_vertex_address instead).
// Binding 7: 2 to 6 are the fragment stage's material buffer and textures.
layout(scalar, set = 0, binding = 7) readonly buffer PreviousVertexBuffer {
    SceneVertex items[];
} previous_vertices;

vec3 previous_position(uint index) {
    if (kSceneAddressed) {
        return scene_vertex_at(push.previous_vertex_address, index).position;
    }
    return previous_vertices.items[index].position;
}

layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 world_normal;
layout(location = 2) out vec4 world_tangent;
layout(location = 3) out vec2 uv0;
layout(location = 4) flat out vec3 face_normal;
layout(location = 5) out vec4 vertex_color;
layout(location = 6) out vec2 uv1;
layout(location = 7) flat out float coordinate_magnitude;  // largest |coordinate| of the triangle's corners
layout(location = 8) out vec3 motion;  // previous position - position: exactly 0 where the vertex did not move

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
    vec3 m = max(abs(scene_triangle_vertex(triangle, 0u).position),
                 max(abs(scene_triangle_vertex(triangle, 1u).position), abs(scene_triangle_vertex(triangle, 2u).position)));
    coordinate_magnitude = max(m.x, max(m.y, m.z));
    motion = vec3(0.0);
    if (push.has_motion != 0u) {
        motion = previous_position(scene_index(uint(gl_VertexIndex))) - v.position;
    }
    gl_Position = push.view_projection * vec4(v.position, 1.0);
}
