#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// GPU BVH refit from the scene's own buffers: each built triangle's three corners gathered from
// the scene's vertex and index buffers (where a GPU pose wrote them) into the build's input
// records, which the refit then reads. Only the positions change: a record's id and alpha stay
// as the build wrote them. The host's refit uploads the same records from host vertices.

#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

// scene::Vertex byte for byte (as raster_scene.glsl declares it).
struct SceneVertex {
    vec3 position;
    vec3 normal;
    vec4 tangent;
    vec2 uv0;
    vec2 uv1;
    vec4 color;
};

// The build's input record (bvh_build.glsl's BvhTriangle, the same struct).
struct BvhTriangle {
    vec3 v0;
    uint id;
    vec3 v1;
    uint alpha;
    vec3 v2;
};

layout(scalar, set = 0, binding = 0) readonly buffer SceneVertexBuffer { SceneVertex items[]; } scene_vertices;
layout(std430, set = 0, binding = 1) readonly buffer SceneIndexBuffer { uint items[]; } scene_indices;
layout(std430, set = 0, binding = 2) readonly buffer KeptTriangleBuffer { uint items[]; } kept_triangles;
layout(std430, set = 0, binding = 3) buffer BvhBuildInputBuffer { BvhTriangle items[]; } input_triangles;

layout(push_constant) uniform BvhRefitGatherPush {
    uint triangle_count;  // built (kept) triangles
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= push.triangle_count) {
        return;
    }
    uint t = kept_triangles.items[i];  // the scene triangle of record i
    input_triangles.items[i].v0 = scene_vertices.items[scene_indices.items[3u * t]].position;
    input_triangles.items[i].v1 = scene_vertices.items[scene_indices.items[3u * t + 1u]].position;
    input_triangles.items[i].v2 = scene_vertices.items[scene_indices.items[3u * t + 2u]].position;
}
