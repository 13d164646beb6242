#version 460
// Forward light cuts: the splatting's indirect draw arguments (VkDrawIndirectCommand) from the
// compaction's kept count, so the splat pass draws one proxy per kept VPL and none for the
// discarded triangles (the FLC paper sec. 5), without a read-back to the host.

layout(local_size_x = 1) in;

layout(std430, set = 0, binding = 0) readonly buffer FlcCountBuffer {
    uint kept;
    uint divergent;
    uint level_counts[];
} counts;

// VkDrawIndirectCommand: vertexCount, instanceCount, firstVertex, firstInstance.
layout(std430, set = 0, binding = 1) writeonly buffer FlcDrawArgs {
    uint vertex_count;
    uint instance_count;
    uint first_vertex;
    uint first_instance;
} draw;

layout(push_constant) uniform FlcSplatArgsPush {
    uint vpl_capacity;  // entries of the VPL buffer: never draw more
} push;

void main() {
    draw.vertex_count = 6u;  // two triangles: the VPL's screen-space rectangle
    draw.instance_count = min(counts.kept, push.vpl_capacity);
    draw.first_vertex = 0u;
    draw.first_instance = 0u;
}
