#ifndef VPLKIT_CUT_BLENDING_GLSL
#define VPLKIT_CUT_BLENDING_GLSL

// Shallow light cuts shared by k x k pixel blocks, and the stochastic blending of the four cuts
// around a pixel (the thesis sec. 5.1.3, Alg. 1: hybrid_gi.comp draws one of them per pixel by
// these weights), with the mock cut as the fallback (sec. 5.1.4).
// Include vplkit/geometric_similarity.glsl first.

// A block's cut record: the pixel whose geometry chose the cut (the covered pixel nearest the
// block's centre), and how many of the block's n cut slots hold a node.
struct HybridBlock {
    vec3 position;  // world position of the representative pixel
    uint covered;   // 0: the block shows only background (no cut, never blended)
    vec3 normal;    // its shading normal
    uint cut_size;  // filled slots; the rest hold kCutEmptySlot
};

const uint kCutEmptySlot = 0xFFFFFFFFu;

// The four blocks whose centres surround `pixel` and their bilinear weights (they sum to 1): a
// block's centre is at pixel (b + 0.5) k - 0.5 along each axis; outside the outermost centres
// the nearest block takes the whole weight (indices clamped, the weights still sum to 1).
void cut_blend_neighbours(ivec2 pixel, uint block_size, ivec2 blocks, out ivec2 block[4], out float weight[4]) {
    vec2 f = (vec2(pixel) + 0.5) / float(block_size) - 0.5;
    vec2 base = floor(f);
    vec2 t = f - base;
    ivec2 b0 = ivec2(base);
    for (int i = 0; i < 4; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        block[i] = clamp(b0 + o, ivec2(0), blocks - 1);
        float wx = o.x == 1 ? t.x : 1.0 - t.x;
        float wy = o.y == 1 ? t.y : 1.0 - t.y;
        weight[i] = wx * wy;
    }
}

// Alg. 1 lines 1-6: bilinear weight x geometric similarity (eq. 5.3) to each block's
// representative pixel, normalized. Returns false (all weights 0) when no block is similar:
// the pixel then uses the mock cut.
bool cut_blend_weights(vec3 x, vec3 n, HybridBlock neighbour[4], float bilinear[4], float min_cos, float max_distance,
                       out float weight[4]) {
    float sum = 0.0;
    for (int i = 0; i < 4; ++i) {
        bool similar = neighbour[i].covered != 0u &&
                       geometrically_similar(x, n, neighbour[i].position, neighbour[i].normal, min_cos, max_distance);
        weight[i] = similar ? bilinear[i] : 0.0;
        sum += weight[i];
    }
    if (!(sum > 0.0)) {
        return false;
    }
    for (int i = 0; i < 4; ++i) {
        weight[i] /= sum;
    }
    return true;
}

// sec. 5.1.4: the mock cut is every node on tree level floor(log2(n)) (the deepest level no
// wider than the per-pixel budget n), or the leaf level of a shallower tree.
uint mock_cut_level(uint cut_size, uint leaf_count) {
    return min(uint(findMSB(cut_size)), uint(findMSB(leaf_count)));
}

#endif
