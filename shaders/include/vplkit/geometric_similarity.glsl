#ifndef VPLKIT_GEOMETRIC_SIMILARITY_GLSL
#define VPLKIT_GEOMETRIC_SIMILARITY_GLSL

// Whether two surface points belong to the same smooth piece of surface (the thesis eq. 5.3):
//   S(x, y) = 1  if <n_x, n_y> > n_min and |p_x - p_y| < d_max,  0 otherwise.
// The edge test of every filter that must not blur across creases and depth jumps: the BRSM
// importance filter, and later cut blending and joint bilateral upsampling.
bool geometrically_similar(vec3 p_x, vec3 n_x, vec3 p_y, vec3 n_y, float min_cos, float max_distance) {
    vec3 d = p_x - p_y;
    return dot(n_x, n_y) > min_cos && dot(d, d) < max_distance * max_distance;
}

#endif
