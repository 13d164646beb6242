#version 460
// With conflict_b.comp: the same struct name, two layouts. Codegen must refuse the pair.
layout(local_size_x = 1) in;
struct Conflict {
  float x;
  float y;
};
layout(std430, binding = 0) buffer ConflictA { Conflict items[]; } a;
void main() { a.items[0].y = 1.0; }
