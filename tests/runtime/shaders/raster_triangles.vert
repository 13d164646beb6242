#version 460
// Test shader: vertex pulling from a storage buffer (clip-space positions), a push-constant block
// shared with the fragment stage, a flat triangle index for the fragment stage.

layout(std430, set = 0, binding = 0) readonly buffer RasterVertexBuffer { vec4 items[]; } vertices;

layout(push_constant) uniform RasterTestPush {
    vec4 colors[2];  // one per triangle
} push;

layout(location = 0) flat out uint triangle;

void main() {
    gl_Position = vertices.items[gl_VertexIndex];
    triangle = uint(gl_VertexIndex) / 3u;
}
