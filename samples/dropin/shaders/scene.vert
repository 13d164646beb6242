#version 460
// The sample renderer's own geometry pass (nothing of vplkit's): world-space triangles with a
// colour per vertex, one view-projection.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;

layout(push_constant) uniform Push {
    mat4 view_projection;
    vec4 light_position;
    vec4 light_color;  // this renderer's units: a surface gets albedo * N.L * light_color / d^2
} push;

layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 world_normal;
layout(location = 2) out vec3 surface_albedo;

void main() {
    world_position = position;
    world_normal = normal;
    surface_albedo = albedo;
    gl_Position = push.view_projection * vec4(position, 1.0);
}
