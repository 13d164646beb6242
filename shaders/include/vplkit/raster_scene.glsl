#ifndef VPLKIT_RASTER_SCENE_GLSL
#define VPLKIT_RASTER_SCENE_GLSL

// The scene's triangles as GpuScene uploads them (runtime/include/vplkit/gpu_scene.hpp), pulled
// from storage buffers by the raster stages' vertex shaders. Draws are non-indexed: vertex
// invocation i belongs to triangle i / 3 (vkCmdDraw with firstVertex = 3 * first triangle), so
// every vertex invocation knows its whole triangle and can hand the exact face normal to the
// fragment stage as a flat input. No vertex input state, no geometry shader (gl_PrimitiveID in
// a fragment shader would need the geometryShader feature).
//
// Including it: enable GL_EXT_scalar_block_layout at the top of the shader and define the set-0
// binding numbers first,
//     #define VPLKIT_SCENE_VERTICES_BINDING 0
//     #define VPLKIT_SCENE_INDICES_BINDING 1
//     #include "vplkit/raster_scene.glsl"
// which declares `scene_vertices` and `scene_indices` (generated Bindings fields of those names).

#if !defined(VPLKIT_SCENE_VERTICES_BINDING) || !defined(VPLKIT_SCENE_INDICES_BINDING)
#error "define VPLKIT_SCENE_VERTICES_BINDING and VPLKIT_SCENE_INDICES_BINDING before including vplkit/raster_scene.glsl"
#endif

// scene::Vertex byte for byte (72 bytes, no padding: hence the scalar layout).
struct SceneVertex {
    vec3 position;  // world space
    vec3 normal;    // world space, unit
    vec4 tangent;   // xyz world space, w = bitangent sign; all zero when no normal texture needs it
    vec2 uv0;
    vec2 uv1;
    vec4 color;     // COLOR_0 (white without one): multiplies the base colour
};

layout(scalar, set = 0, binding = VPLKIT_SCENE_VERTICES_BINDING) readonly buffer SceneVertexBuffer {
    SceneVertex items[];
} scene_vertices;

// Three indices per triangle, counter-clockwise = front (the loader keeps mirrored instances CCW).
layout(std430, set = 0, binding = VPLKIT_SCENE_INDICES_BINDING) readonly buffer SceneIndexBuffer {
    uint items[];
} scene_indices;

SceneVertex scene_triangle_vertex(uint triangle, uint corner) {
    return scene_vertices.items[scene_indices.items[3u * triangle + corner]];
}

// Unit normal of the triangle's front (counter-clockwise) side; zero for a triangle too thin to
// have one in float (the fragment stage then falls back to the interpolated normal). The cross
// product is scaled by its largest component before squaring, so tiny (1e-3 scale) triangles
// do not underflow.
vec3 scene_face_normal(uint triangle) {
    vec3 p0 = scene_vertices.items[scene_indices.items[3u * triangle]].position;
    vec3 p1 = scene_vertices.items[scene_indices.items[3u * triangle + 1u]].position;
    vec3 p2 = scene_vertices.items[scene_indices.items[3u * triangle + 2u]].position;
    vec3 n = cross(p1 - p0, p2 - p0);
    float largest = max(abs(n.x), max(abs(n.y), abs(n.z)));
    return largest > 0.0 ? normalize(n / largest) : vec3(0.0);
}

#endif
