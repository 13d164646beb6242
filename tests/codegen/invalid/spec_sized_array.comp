#version 460
// An array inside a block sized by a specialization constant: its size is unknown when the
// header is written.
layout(local_size_x = 1) in;
layout(constant_id = 0) const uint kCount = 4;
layout(std430, binding = 0) buffer SpecSized {
  float values[kCount];
} spec_sized;
void main() { spec_sized.values[0] = 1.0; }
