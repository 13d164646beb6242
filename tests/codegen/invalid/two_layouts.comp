#version 460
// One struct in a std140 and a std430 block: glslang gives it two layouts (array stride 16
// vs 4) under one name, which one C++ struct cannot mirror.
layout(local_size_x = 1) in;
struct Pair {
  float values[2];
};
layout(std140, binding = 0) uniform Params { Pair pair; } params;
layout(std430, binding = 1) buffer Data { Pair pair; } data;
void main() { data.pair = params.pair; }
