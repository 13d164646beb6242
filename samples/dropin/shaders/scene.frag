#version 460
// The sample renderer's shading: colour = albedo * N.L * light / d^2 (no 1 / pi, no shadows),
// plus the octahedral normal and the albedo it keeps for its post passes.
layout(push_constant) uniform Push {
    mat4 view_projection;
    vec4 light_position;
    vec4 light_color;
} push;

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec3 surface_albedo;

layout(location = 0) out vec4 colour;             // RGBA16F
layout(location = 1) out vec2 octahedral_normal;  // RG16F, world space
layout(location = 2) out vec4 albedo;             // RGBA8 UNORM

// Cigolle et al. 2014: n.xy / |n|_1, folded over the diagonals where n.z < 0.
vec2 octahedral(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.xy;
    if (n.z < 0.0) {
        e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    }
    return e;
}

void main() {
    vec3 n = normalize(world_normal);
    vec3 to_light = push.light_position.xyz - world_position;
    float d2 = dot(to_light, to_light);
    float n_dot_l = max(dot(n, to_light * inversesqrt(d2)), 0.0);
    colour = vec4(surface_albedo * n_dot_l * push.light_color.rgb / d2, 1.0);
    octahedral_normal = octahedral(n);
    albedo = vec4(surface_albedo, 1.0);
}
