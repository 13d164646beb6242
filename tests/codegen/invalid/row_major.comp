#version 460
// A row_major matrix: rejected (column-major only).
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Transforms {
  layout(row_major) mat4 transform;
} transforms;
void main() { transforms.transform[0][0] = 1.0; }
