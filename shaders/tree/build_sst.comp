#version 460
#extension GL_GOOGLE_include_directive : require
// Builds every inner node of the Stochastic Substitute Tree in one bottom-up dispatch (the SST paper
// sec. 3.3 and 5, the thesis sec. 4.2.2): one thread per pair of leaves merges its pair into their
// parent, then climbs. At each inner node above, the first of its two subtrees' threads to
// arrive stops and the second merges both children and goes on, so exactly one thread reaches
// the root. No thread ever waits for another workgroup (Vulkan promises no forward progress
// between workgroups): a thread either has both children finished or leaves the work to the
// thread that will finish the other one. The only waits are workgroup barriers, which every
// thread of the workgroup reaches.
//
// Layout and padding rules: see vplkit/sst.glsl. The host clears `counters` to 0 before this
// dispatch (one per inner node above the lowest inner level).

#include "vplkit/sst.glsl"
#include "vplkit/dispatch.glsl"
#include "vplkit/element_count.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer LeafBuffer { Vpl items[]; } leaves;
// coherent: a node written by one workgroup is read by a thread of another within this
// dispatch, so its stores and loads must not stay in a non-coherent per-workgroup cache.
layout(std430, set = 0, binding = 1) coherent buffer SstNodeBuffer { SstNode items[]; } nodes;
// Arrivals per inner node; index = node index (the lowest inner level needs none).
layout(std430, set = 0, binding = 2) buffer SstCounterBuffer { uint items[]; } counters;
VPLKIT_DECLARE_ELEMENT_COUNT(3)

layout(push_constant) uniform BuildSstPush {
    uint count;        // real VPLs (leaves at index >= count are bogus), or the capacity (count_word)
    uint leaf_count;   // L: count rounded up to a power of two
    float nu_min;      // the SST paper eq. 3 thresholds
    float sigma_max;   // world units (a standard deviation along the normal)
    uint count_word;   // element_count.glsl
} push;

// Whether any thread of the workgroup is still climbing, per loop step (three slots; see below).
shared uint workgroup_climbing[3];

SstNode leaf_node(uint leaf) {
    return leaf < element_count(push.count, push.count_word) ? sst_leaf_node(leaves.items[leaf], push.nu_min, push.sigma_max) : sst_empty_node();
}

void main() {
    uint pair = linear_thread_index();
    uint half_leaves = push.leaf_count >> 1;
    if (push.leaf_count == 1u) {  // uniform across the dispatch
        if (pair == 0u) {
            nodes.items[0] = leaf_node(0u);  // one VPL: the root is the leaf
        }
        return;
    }

    // The lowest inner level has one thread per node: nothing to wait for.
    bool climbing = pair < half_leaves;
    uint node_index = 0u;
    SstNode node;
    if (climbing) {
        node_index = half_leaves - 1u + pair;
        node = sst_merge(leaf_node(2u * pair), leaf_node(2u * pair + 1u), push.nu_min, push.sigma_max);
        nodes.items[node_index] = node;
        climbing = node_index != 0u;
    }

    // Every barrier below is reached by the whole workgroup (the loop ends for all of its threads
    // at once): Vulkan allows memory barriers in divergent code, but lavapipe (Mesa 22) runs
    // them like workgroup barriers and then drops threads that climb past others that returned.
    // Each step, threads still climbing flag a slot, and the workgroup leaves the loop once no
    // thread flagged it. Three slots: the one flagged in step s is read after that step's
    // barrier, and reset by thread 0 at the start of step s + 2, after step s + 1's barrier
    // (everyone has read it) and before step s + 2's barrier (before anyone flags it again).
    if (gl_LocalInvocationIndex == 0u) {
        workgroup_climbing[0] = 0u;
        workgroup_climbing[1] = 0u;
        workgroup_climbing[2] = 0u;
    }
    barrier();
    for (uint step = 0u;; ++step) {
        uint slot = step % 3u;
        if (gl_LocalInvocationIndex == 0u) {
            workgroup_climbing[(step + 1u) % 3u] = 0u;
        }
        if (climbing) {
            atomicOr(workgroup_climbing[slot], 1u);
        }
        barrier();
        if (workgroup_climbing[slot] == 0u) {
            break;
        }

        // The arrival counter with fences around it: the first thread to arrive at a parent
        // stored its node (to a coherent buffer, so it is not held in a per-workgroup cache),
        // then passed a release fence, then incremented. The second thread's increment reads
        // the first one's (atomics on one location are totally ordered), so the first thread's
        // release fence synchronizes with the second thread's acquire fence after its
        // increment (fence-atomic-atomic-fence): its loads of the sibling see the stored node.
        // memoryBarrierBuffer() is OpMemoryBarrier(Device, AcquireRelease | UniformMemory).
        memoryBarrierBuffer();
        uint arrived_before = 0u;
        uint parent = 0u;
        if (climbing) {
            parent = sst_parent(node_index);
            arrived_before = atomicAdd(counters.items[parent], 1u);
        }
        memoryBarrierBuffer();

        if (climbing) {
            if (arrived_before == 0u) {
                climbing = false;  // the sibling subtree is unfinished; its thread merges this parent
            } else {
                uint sibling = (node_index & 1u) != 0u ? node_index + 1u : node_index - 1u;
                SstNode other = nodes.items[sibling];
                // Left/right by index, never by arrival order, so the result is deterministic.
                node = (node_index & 1u) != 0u ? sst_merge(node, other, push.nu_min, push.sigma_max)
                                               : sst_merge(other, node, push.nu_min, push.sigma_max);
                node_index = parent;
                nodes.items[node_index] = node;
                climbing = node_index != 0u;
            }
        }
    }
}
