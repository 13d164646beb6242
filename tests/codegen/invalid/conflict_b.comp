#version 460
// With conflict_a.comp: 'y' moves from offset 4 to offset 16.
layout(local_size_x = 1) in;
struct Conflict {
  float x;
  vec3 y;
};
layout(std430, binding = 0) buffer ConflictB { Conflict items[]; } b;
void main() { b.items[0].y = vec3(1.0); }
