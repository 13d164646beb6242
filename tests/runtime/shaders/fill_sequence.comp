#version 460
// Runtime tests only: values[i] = i * scale + offset for i < count. The workgroup size is a
// specialization constant so the tests can check pipelines are cached per specialization.

layout(local_size_x_id = 0) in;

layout(std430, set = 0, binding = 0) writeonly buffer SequenceOutput { uint values[]; } dst;

layout(push_constant) uniform FillSequencePush {
    uint count;
    uint scale;
    uint offset;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < push.count) dst.values[i] = i * push.scale + push.offset;
}
