#ifndef VPLKIT_DISPATCH_GLSL
#define VPLKIT_DISPATCH_GLSL

// The element index of a 1D pass, over a grid that may be folded into 2D. Every device takes
// 65,535 workgroups per dimension (maxComputeWorkGroupCount's required minimum), so the
// generated Pipeline::dispatch() lays a 1D dispatch of more groups out as rows of at most
// 65,535 (docs/codegen.md, "Dispatches past 65,535 workgroups"). A shader that calls these
// functions is folded; one that reads gl_GlobalInvocationID or gl_WorkGroupID.x instead would
// see row 1 repeat row 0, so codegen folds only shaders that call them (and refuses a shader
// that also reads gl_GlobalInvocationID).
//
// The last row may hold a few groups past the count: every caller bounds-checks its index
// (a tiled shader its workgroup index, before its first barrier).
// The workgroup must be 1D (local_size_y = local_size_z = 1).

// The workgroup's index in the unfolded 1D grid.
uint linear_workgroup_index() {
    return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
}

// The two below are macros, not functions: gl_WorkGroupSize is a constant taken where it is
// written, and a function body in an include that comes before the shader's
// `layout(local_size_x ...) in;` would see the default size 1. A macro is expanded in main().

// The thread's index in the unfolded 1D grid: gl_GlobalInvocationID.x of an unfolded dispatch.
#define linear_thread_index() (linear_workgroup_index() * gl_WorkGroupSize.x + gl_LocalInvocationID.x)

// Threads in the whole (folded) grid, for grid-stride loops.
#define linear_thread_count() (gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_WorkGroupSize.x)

#endif
