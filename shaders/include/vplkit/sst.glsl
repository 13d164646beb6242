#ifndef VPLKIT_SST_GLSL
#define VPLKIT_SST_GLSL

// Stochastic Substitute Tree (the SST paper sec. 3; the thesis sec. 4.2): a perfect binary tree over the
// sorted, power-of-two padded leaf array (tree/gather_leaves.comp) whose inner nodes hold a
// substitute distribution of their VPLs: a normal distribution on the plane through the node's
// intensity-weighted mean with the node's merged normal, with a variance per axis of the node's
// tangent frame (sst_frame).
//
// Indexing (heap order): with L leaves (a power of two) there are L - 1 inner nodes, the root is
// node 0 and the children of node i are 2i + 1 and 2i + 2. A child index c >= L - 1 is leaf
// c - (L - 1): leaves are not stored as nodes (they are the leaf buffer's Vpls; sst_leaf_node()
// turns one into a node when needed), which halves the tree's memory (the thesis sec. 4.2.2 on
// the perfect tree's smaller footprint) and keeps 2^20 VPLs' nodes (~96 MiB) inside a 128 MiB
// storage-buffer range. For one VPL (L = 1) node 0 is leaf 0; the builder then
// still writes nodes[0] = sst_leaf_node(leaf 0), so nodes[0] always describes the whole tree.
//
// Leaves with index >= count are bogus padding: they are told apart by index, never by their
// data, and become empty nodes (leaf_count 0). A merge with an empty child returns the other
// child unchanged, so padding never moves a mean, a box, a variance or a normal similarity.

#include "vplkit/vpl.glsl"

// 96 bytes, six 16-byte rows, like the SST paper sec. 3.3's node; no ids or child links (implicit).
struct SstNode {
    vec3 mean;         // intensity-weighted mean position (the SST paper eq. 1), world space
    float intensity;   // summed luminance of the VPLs' flux: the merge weight c (the SST paper eq. 1)
    vec3 normal;       // unit; intensity-weighted, renormalized (the thesis sec. 4.2.2)
    float nu;          // normal similarity (the SST paper sec. 3.2; the thesis eq. 4.3); 1 at leaves
    vec3 variance;     // in the frame sst_frame(normal): x tangent, y bitangent, z normal (>= 0)
    uint flags;        // kSstFlag* bits
    vec3 box_lo;       // bounding box of the real VPLs below (a point at a leaf)
    uint leaf_count;   // real (non-bogus) VPLs below; 0: an empty node, every other field zero
    vec3 box_hi;
    vec3 colour;       // summed RGB flux
};

// the SST paper eq. 3 / the thesis eq. 5.6: nu >= nu_min and sigma_z <= sigma_max, decided at build time.
const uint kSstFlagSuitable = 1u;
// The merged normal was too short to normalize (children facing opposite ways with about equal
// weights) and is the brighter child's normal instead; nu is 0 there, so never suitable.
const uint kSstFlagNormalFallback = 2u;

// Below this length, a * n1 + b * n2 (a + b = 1) is replaced by the brighter child's normal:
// float rounding (~1e-7 per component) would turn a shorter sum into a direction of noise.
// At 1e-3 the renormalized direction is still good to ~1e-4 rad.
const float kSstMinMergedNormalLength = 1e-3;

// The tangent frame is a function of the normal alone (sampling rebuilds it from node.normal):
// the shortest rotation taking the fixed axis h onto n, applied to a fixed tangent u of h
// (Rodrigues: R u = c u + k x u + (k . u) / (1 + c) k with c = h . n, k = h x n), then
// re-orthonormalized. It is continuous everywhere except at n = -h, so nearby normals (float
// and double, or a child and its parent) get nearby frames; an axis-by-axis switch (Duff et
// al. 2017's branchless basis jumps at n.z = 0, every vertical wall) would not. -h is 19+
// degrees from every axis, face-diagonal and space-diagonal direction (walls, floors,
// ceilings), so those get well-conditioned frames; within ~0.8 degrees of -h (1 + c < 1e-4)
// the frame is u's, where the rotation would divide by almost 0.
const vec3 kSstFrameAxis = vec3(0.26726124, 0.53452248, 0.80178373);     // (1, 2, 3) / sqrt(14)
const vec3 kSstFrameTangent = vec3(0.89442719, -0.44721360, 0.0);        // (2, -1, 0) / sqrt(5)
const float kSstFramePoleGuard = 1e-4;

// Right-handed orthonormal (t, b, n) for a unit normal n.
void sst_frame(vec3 n, out vec3 t, out vec3 b) {
    float c = dot(kSstFrameAxis, n);
    vec3 t0 = kSstFrameTangent;
    if (1.0 + c > kSstFramePoleGuard) {
        vec3 k = cross(kSstFrameAxis, n);
        t0 = c * kSstFrameTangent + cross(k, kSstFrameTangent) + (dot(k, kSstFrameTangent) / (1.0 + c)) * k;
    }
    vec3 bt = cross(n, t0);
    b = bt * inversesqrt(dot(bt, bt));
    t = cross(b, n);
}

// Relative luminance of linear RGB (Rec. 709 weights): the "grayscale intensity" that weights
// merges (the thesis eq. 4.1, the SST paper sec. 3.2). Negative or NaN luminance counts as 0, so a
// weight is never negative (the comparison is false for NaN).
float sst_intensity(vec3 flux) {
    float y = dot(flux, vec3(0.2126, 0.7152, 0.0722));
    return y > 0.0 ? y : 0.0;
}

float sst_sigma_z(SstNode node) {
    return sqrt(node.variance.z);
}

// the SST paper eq. 3 (the thesis eq. 5.6). sigma_max is in world units: sigma_z is the standard
// deviation along the normal, a length (both papers compare it with an absolute threshold).
bool sst_is_suitable(float nu, float sigma_z, float nu_min, float sigma_max) {
    return nu >= nu_min && sigma_z <= sigma_max;
}

SstNode sst_empty_node() {
    return SstNode(vec3(0.0), 0.0, vec3(0.0), 0.0, vec3(0.0), 0u, vec3(0.0), 0u, vec3(0.0), vec3(0.0));
}

// A leaf as a node: variance 0 and the mean at the VPL (the SST paper sec. 3.2), nu = 1 (sec. 3.3).
// A zero normal (invalid input) becomes +z so that frames and dot products stay finite.
SstNode sst_leaf_node(Vpl vpl, float nu_min, float sigma_max) {
    float n2 = dot(vpl.normal, vpl.normal);
    vec3 n = n2 > 0.0 ? vpl.normal * inversesqrt(n2) : vec3(0.0, 0.0, 1.0);
    uint flags = sst_is_suitable(1.0, 0.0, nu_min, sigma_max) ? kSstFlagSuitable : 0u;
    return SstNode(vpl.position, sst_intensity(vpl.flux), n, 1.0, vec3(0.0), flags, vpl.position, 1u,
                   vpl.position, vpl.flux);
}

// A child's axis variances re-expressed in the parent frame (t, b, n): the diagonal of R S R^T
// for the child's diagonal covariance S rotated from its own frame. The SST paper eq. 2 adds the
// child's variance unrotated, which the paper notes is invalid when normals diverge; the
// rotation keeps each variance >= 0 and the trace (total variance) unchanged.
vec3 sst_variance_in_frame(SstNode child, vec3 t, vec3 b, vec3 n) {
    if (child.variance == vec3(0.0)) {
        return vec3(0.0);  // leaves and coincident VPLs: no frame needed (half of all merges)
    }
    vec3 ct, cb;
    sst_frame(child.normal, ct, cb);
    vec3 v = child.variance;
    vec3 dt = vec3(dot(t, ct), dot(t, cb), dot(t, child.normal));
    vec3 db = vec3(dot(b, ct), dot(b, cb), dot(b, child.normal));
    vec3 dn = vec3(dot(n, ct), dot(n, cb), dot(n, child.normal));
    return vec3(dot(dt * dt, v), dot(db * db, v), dot(dn * dn, v));
}

// Merges the two children of a node; `left` is the lower-index child, so the result does not
// depend on which child was finished first.
SstNode sst_merge(SstNode left, SstNode right, float nu_min, float sigma_max) {
    if (left.leaf_count == 0u) {
        return right;
    }
    if (right.leaf_count == 0u) {
        return left;
    }
    // Normalized weights; two dark children (0/0) count equally, so mean and normal stay
    // defined (the midpoint and the mean direction) while the intensity stays 0.
    float w = left.intensity + right.intensity;
    float a = w > 0.0 ? left.intensity / w : 0.5;
    float b = w > 0.0 ? right.intensity / w : 0.5;

    SstNode node;
    // the SST paper eq. 1 as p1 + b (p2 - p1): stays between the children far from the origin, and
    // coincident children give exactly their position and d = 0.
    vec3 d = right.mean - left.mean;
    node.mean = left.mean + b * d;
    node.intensity = w;

    // the thesis sec. 4.2.2: the normal merged like the position, then renormalized.
    vec3 m = a * left.normal + b * right.normal;
    float m2 = dot(m, m);
    node.flags = 0u;
    if (m2 >= kSstMinMergedNormalLength * kSstMinMergedNormalLength) {
        node.normal = m * inversesqrt(m2);
    } else {
        node.normal = right.intensity > left.intensity ? right.normal : left.normal;
        node.flags |= kSstFlagNormalFallback;
    }
    // the SST paper sec. 3.2, the thesis eq. 4.3.
    node.nu = left.nu * right.nu * max(dot(left.normal, right.normal), 0.0);

    // the SST paper eq. 2 (the thesis eq. 4.2) in Chan et al.'s pairwise form: with p = a p1 + b p2,
    // a (s1 + D1 (.) D1) + b (s2 + D2 (.) D2) = a s1 + b s2 + a b d (.) d, D_i = p_i - p, d = p2 - p1.
    // Every term is >= 0 (no E[x^2] - E[x]^2 cancellation) and d is a difference of nearby means.
    vec3 t, bt;
    sst_frame(node.normal, t, bt);
    vec3 dl = vec3(dot(d, t), dot(d, bt), dot(d, node.normal));
    node.variance = a * sst_variance_in_frame(left, t, bt, node.normal) +
                    b * sst_variance_in_frame(right, t, bt, node.normal) + (a * b) * (dl * dl);

    node.box_lo = min(left.box_lo, right.box_lo);
    node.box_hi = max(left.box_hi, right.box_hi);
    node.leaf_count = left.leaf_count + right.leaf_count;
    node.colour = left.colour + right.colour;
    if (sst_is_suitable(node.nu, sst_sigma_z(node), nu_min, sigma_max)) {
        node.flags |= kSstFlagSuitable;
    }
    return node;
}

// Heap-order navigation; leaf_count is the (power-of-two) number of leaves L.
uint sst_left_child(uint node) { return 2u * node + 1u; }
uint sst_right_child(uint node) { return 2u * node + 2u; }
uint sst_parent(uint node) { return (node - 1u) >> 1; }
bool sst_is_leaf(uint node, uint leaf_count) { return node >= leaf_count - 1u; }
uint sst_leaf_index(uint node, uint leaf_count) { return node - (leaf_count - 1u); }

#endif
