#ifndef VPLKIT_VPL_GLSL
#define VPLKIT_VPL_GLSL

// A virtual point light: a point on a surface that re-emits light it received.
// std430 puts each vec3 in its own 16-byte slot; codegen writes the padding out on the C++ side.
struct Vpl {
    vec3 position;  // world space
    vec3 normal;    // unit length, the side the VPL emits into
    vec3 flux;      // RGB radiant flux
};

#endif
