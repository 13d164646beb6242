#version 460
// A binding in descriptor set 1: vplkit shaders use set 0 only.
layout(local_size_x = 1) in;
layout(std430, set = 1, binding = 2) buffer Elsewhere { uint data[]; } elsewhere;
void main() { elsewhere.data[0] = 1; }
