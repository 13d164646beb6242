#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// Poses vertices on the GPU: each rest vertex (its primitive's object space) morphed by its
// instance's targets at this frame's weights, then moved by the blend of its joints' matrices
// (joint world x inverse bind; a rigid instance has one matrix, its node's world transform), and
// written into the scene's vertex buffer at its own index. Only position, normal and tangent are
// written: texture coordinates and colours stay as uploaded. The arithmetic is the host loader's
// (runtime/src/scene/gltf_pose.cpp and gltf_geometry.cpp's append_instance) in float:
//   p' = M p,  M = sum_k w_k J[j_k] / sum_k w_k  (glTF 2.0 3.7.3; weights rescaled to sum 1)
//   n' = normalize(sign(det L) cof(L) n),  L the linear part of M (cof(L) = det L x L^-T: finite
//        for a singular blend)
//   t' = Gram-Schmidt of L t against n', w' = sign(t.w) x sign(det L) (a mirroring pose flips it)

#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

// One vertex to pose, in its primitive's object space (its mesh's, before morphs and skin).
struct PoseRestVertex {
    vec3 position;
    uint instance;  // index into pose_instances
    vec3 normal;
    uint vertex;    // where it goes in the scene's vertex buffer
    vec4 tangent;   // xyz, w = handedness (+1 or -1); unused when the instance has no tangents
    uvec4 joints;   // indices into the instance's matrices (skinned instances only)
    vec4 weights;   // their weights; 0 slots are skipped (an unused slot may name any joint)
};

// One node's instance of one primitive: where its data lie in the other buffers.
struct PoseInstance {
    uint first_rest_vertex;  // its first vertex in rest_vertices
    uint vertex_count;
    uint first_matrix;       // into pose_matrices
    uint skinned;            // 1: blend joints[] by weights[]; 0: pose_matrices[first_matrix] alone
    uint first_delta;        // into morph_deltas: target k's delta of vertex v at first_delta + k * vertex_count + v
    uint target_count;
    uint first_weight;       // into morph_weights: target k's weight at first_weight + k
    uint has_tangents;       // 1: tangents are posed; 0: left as they are (zero)
};

// One morph target's displacement of one vertex (w unused).
struct MorphDelta {
    vec4 position;
    vec4 normal;
    vec4 tangent;
};

// scene::Vertex byte for byte (as raster_scene.glsl declares it).
struct SceneVertex {
    vec3 position;
    vec3 normal;
    vec4 tangent;
    vec2 uv0;
    vec2 uv1;
    vec4 color;
};

layout(std430, set = 0, binding = 0) readonly buffer PoseRestVertexBuffer { PoseRestVertex items[]; } rest_vertices;
layout(std430, set = 0, binding = 1) readonly buffer PoseInstanceBuffer { PoseInstance items[]; } pose_instances;
layout(std430, set = 0, binding = 2) readonly buffer PoseMatrixBuffer { mat4 items[]; } pose_matrices;
layout(std430, set = 0, binding = 3) readonly buffer MorphDeltaBuffer { MorphDelta items[]; } morph_deltas;
layout(std430, set = 0, binding = 4) readonly buffer MorphWeightBuffer { float items[]; } morph_weights;
layout(scalar, set = 0, binding = 5) buffer SceneVertexBuffer { SceneVertex items[]; } posed_vertices;

layout(push_constant) uniform PoseVerticesPush {
    uint vertex_count;  // rest vertices to pose
} push;

// A unit vector orthogonal to n, as the loader picks it (gltf_geometry.cpp's any_orthogonal).
vec3 any_orthogonal(vec3 n) {
    vec3 a = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    return normalize(a - n * dot(n, a));
}

void main() {
    uint i = linear_thread_index();
    if (i >= push.vertex_count) {
        return;
    }
    PoseRestVertex rest = rest_vertices.items[i];
    PoseInstance instance = pose_instances.items[rest.instance];
    uint local = i - instance.first_rest_vertex;

    // glTF 2.0 3.7.2.2: the base plus the weighted sum of the targets' displacements.
    vec3 position = rest.position;
    vec3 normal = rest.normal;
    vec3 tangent = rest.tangent.xyz;
    for (uint k = 0u; k < instance.target_count; ++k) {
        float w = morph_weights.items[instance.first_weight + k];
        if (w == 0.0) {
            continue;
        }
        MorphDelta d = morph_deltas.items[instance.first_delta + k * instance.vertex_count + local];
        position += w * d.position.xyz;
        normal += w * d.normal.xyz;
        tangent += w * d.tangent.xyz;
    }

    mat4 m = pose_matrices.items[instance.first_matrix];
    if (instance.skinned != 0u) {
        m = mat4(0.0);
        float total = 0.0;
        for (int k = 0; k < 4; ++k) {
            float w = rest.weights[k];
            if (w == 0.0) {
                continue;
            }
            m += w * pose_matrices.items[instance.first_matrix + rest.joints[k]];
            total += w;
        }
        m *= 1.0 / total;  // the loader refuses a vertex whose weights are all zero
    }
    mat3 l = mat3(m);
    float det = dot(l[0], cross(l[1], l[2]));
    mat3 cofactor = mat3(cross(l[1], l[2]), cross(l[2], l[0]), cross(l[0], l[1]));
    vec3 n = cofactor * normal;
    n = det < 0.0 ? -n : n;
    float n_length = length(n);
    // A zero normal stays the rest one turned by the pose (the host repairs it from the faces).
    n = n_length > 0.0 ? n / n_length : normalize(l * rest.normal);

    posed_vertices.items[rest.vertex].position = (m * vec4(position, 1.0)).xyz;
    posed_vertices.items[rest.vertex].normal = n;
    if (instance.has_tangents != 0u) {
        vec3 t = l * tangent;
        t -= n * dot(n, t);
        float t_length = length(t);
        float handedness = (rest.tangent.w < 0.0 ? -1.0 : 1.0) * (det < 0.0 ? -1.0 : 1.0);
        posed_vertices.items[rest.vertex].tangent = vec4(t_length > 0.0 ? t / t_length : any_orthogonal(n), handedness);
    }
}
