#version 460
// Test shader: the triangle's push-constant colour, its index in alpha.

layout(push_constant) uniform RasterTestPush {
    vec4 colors[2];
} push;

layout(location = 0) flat in uint triangle;
layout(location = 0) out vec4 color;

void main() {
    color = vec4(push.colors[triangle].rgb, float(triangle));
}
