#ifndef VPLKIT_RASTER_SCENE_GLSL
#define VPLKIT_RASTER_SCENE_GLSL

// The scene's triangles as GpuScene uploads them (runtime/include/vplkit/gpu_scene.hpp), pulled
// from storage buffers by the raster stages' vertex shaders. Draws are non-indexed: vertex
// invocation i belongs to triangle i / 3 (vkCmdDraw with firstVertex = 3 * first triangle), so
// every vertex invocation knows its whole triangle and can hand the exact face normal to the
// fragment stage as a flat input. No vertex input state, no geometry shader (gl_PrimitiveID in
// a fragment shader would need the geometryShader feature).
//
// Including it: enable GL_EXT_scalar_block_layout at the top of the shader, declare the push
// constant block with the scene's addresses (below), and define the set-0 binding numbers and the
// push block's instance name first,
//     #define VPLKIT_SCENE_VERTICES_BINDING 0
//     #define VPLKIT_SCENE_INDICES_BINDING 1
//     #define VPLKIT_SCENE_PUSH push
//     #include "vplkit/raster_scene.glsl"
// which declares `scene_vertices` and `scene_indices` (generated Bindings fields of those names).
//
// Where vertices and indices are read: through those bindings, or, for buffers larger than a
// binding's range (maxStorageBufferRange: 128 MiB on lavapipe, 1.86M vertices), at their buffer
// device addresses (GL_EXT_buffer_reference), which the push block's fields
//     uvec2 scene_vertex_address;  // of scene_vertices' first vertex
//     uvec2 scene_index_address;   // of scene_indices' first index
//     uint scene_vertex_count;     // vertices and indices there: indices are clamped below them,
//     uint scene_index_count;      // so a bad index reads a wrong vertex, never outside the buffer
// hold; the specialization constant kSceneAddressed (SceneBuffers::addressed) picks one, as
// bvh.glsl's kBvhAddressed does, so each pipeline has one path: lavapipe loads through a pointer
// more slowly (docs/architecture.md), and scenes within the range keep the bindings. With
// kSceneAddressed the bindings stay bound, one record wide (a descriptor set has every binding
// filled). Why not fixed-function vertex input (whose vertex buffers have no such range): each
// vertex invocation reads all three corners of its triangle, for the flat face normal.

#if !defined(VPLKIT_SCENE_VERTICES_BINDING) || !defined(VPLKIT_SCENE_INDICES_BINDING)
#error "define VPLKIT_SCENE_VERTICES_BINDING and VPLKIT_SCENE_INDICES_BINDING before including vplkit/raster_scene.glsl"
#endif

#ifdef VPLKIT_SCENE_PUSH
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
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

#ifdef VPLKIT_SCENE_PUSH
// The same arrays at the push block's addresses (kSceneAddressed).
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer SceneVertexArray {
    SceneVertex items[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer SceneIndexArray {
    uint items[];
};

// stages::SceneBuffers::addressed sets it.
layout(constant_id = 30) const bool kSceneAddressed = false;

uint scene_index(uint position) {
    if (kSceneAddressed) {
        uint last = max(VPLKIT_SCENE_PUSH.scene_index_count, 1u) - 1u;
        return SceneIndexArray(VPLKIT_SCENE_PUSH.scene_index_address).items[min(position, last)];
    }
    return scene_indices.items[position];
}

// Vertex `index` of a vertex array at `address` (one of scene_vertex_count vertices).
SceneVertex scene_vertex_at(uvec2 address, uint index) {
    uint last = max(VPLKIT_SCENE_PUSH.scene_vertex_count, 1u) - 1u;
    return SceneVertexArray(address).items[min(index, last)];
}

SceneVertex scene_vertex(uint index) {
    if (kSceneAddressed) {
        return scene_vertex_at(VPLKIT_SCENE_PUSH.scene_vertex_address, index);
    }
    return scene_vertices.items[index];
}

#else
// Without VPLKIT_SCENE_PUSH: through the bindings only (within maxStorageBufferRange).
uint scene_index(uint position) {
    return scene_indices.items[position];
}

SceneVertex scene_vertex(uint index) {
    return scene_vertices.items[index];
}
#endif

SceneVertex scene_triangle_vertex(uint triangle, uint corner) {
    return scene_vertex(scene_index(3u * triangle + corner));
}

// Unit normal of the triangle's front (counter-clockwise) side; zero for a triangle too thin to
// have one in float (the fragment stage then falls back to the interpolated normal). The cross
// product is scaled by its largest component before squaring, so tiny (1e-3 scale) triangles
// do not underflow.
vec3 scene_face_normal(uint triangle) {
    vec3 p0 = scene_triangle_vertex(triangle, 0u).position;
    vec3 p1 = scene_triangle_vertex(triangle, 1u).position;
    vec3 p2 = scene_triangle_vertex(triangle, 2u).position;
    vec3 n = cross(p1 - p0, p2 - p0);
    float largest = max(abs(n.x), max(abs(n.y), abs(n.z)));
    return largest > 0.0 ? normalize(n / largest) : vec3(0.0);
}

#endif
