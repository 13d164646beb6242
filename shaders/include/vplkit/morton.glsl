#ifndef VPLKIT_MORTON_GLSL
#define VPLKIT_MORTON_GLSL

#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

// VPL sort key (the SST paper eq. 4: C = M (+) N (+) id, bit concatenation):
//   bits 63..34  30-bit Morton code of the position, 10 bits per axis
//   bits 33..25   9-bit normal code: 3 octant bits + 3 x 2 triangle-subdivision bits
//   bits 24..0   25-bit unique id (the VPL's index), so no two keys are equal
const uint kMortonBitsPerAxis = 10u;
const uint kNormalCodeBits = 9u;
const uint kIdBits = 25u;
const uint kMaxKeyedVpls = 1u << kIdBits;

// Spreads the low 10 bits of v so that there are two zero bits between each.
uint spread_bits_by_3(uint v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

// x in the highest bit of each triple, then y, then z.
uint morton_code_30(uvec3 cell) {
    return (spread_bits_by_3(cell.x) << 2) | (spread_bits_by_3(cell.y) << 1) | spread_bits_by_3(cell.z);
}

// Cell of `p` in a 1024^3 grid over the box [lo, hi], each axis normalized on its own (Karras 2012).
// An axis of zero extent (all VPLs in one plane, or at one point) maps to cell 0 instead of 0/0;
// a non-finite coordinate also maps to 0 (the host rejects those before they get here).
uvec3 morton_cell(vec3 p, vec3 lo, vec3 hi) {
    uvec3 cell;
    for (int axis = 0; axis < 3; ++axis) {
        float extent = hi[axis] - lo[axis];
        float t = extent > 0.0 ? (p[axis] - lo[axis]) / extent : 0.0;
        t = (t >= 0.0) ? min(t, 1.0) : 0.0;  // also sends NaN to 0: comparisons with NaN are false
        cell[axis] = min(uint(t * 1024.0), 1023u);
    }
    return cell;
}

// Normal code (the SST paper sec. 3.3, Fig. 3): the octant (sign bits of x, y, z), then the point of
// the octant's triangle [Px, Py, Pz] the normal goes through, refined three times. Each refinement
// splits the triangle at its edge midpoints into three corner triangles and the central one:
//   00 corner at Py, 01 corner at Pz, 10 corner at Px, 11 the central triangle.
// Barycentrics are the L1-normalized absolute components, which makes the split equal-area on the
// octahedron and roughly so on the sphere (Taubin and Rossignac 1998).
// A point exactly on a split edge goes to the central triangle (strict comparisons).
uint normal_code_9(vec3 n) {
    uint octant = (n.x < 0.0 ? 4u : 0u) | (n.y < 0.0 ? 2u : 0u) | (n.z < 0.0 ? 1u : 0u);
    vec3 a = abs(n);
    float l1 = a.x + a.y + a.z;
    vec3 bary = l1 > 0.0 ? a / l1 : vec3(1.0 / 3.0);  // a zero normal has no direction: centre of the octant
    uint code = octant;
    for (int level = 0; level < 3; ++level) {
        uint sub;
        if (bary.x > 0.5) {
            sub = 2u; bary = vec3(2.0 * bary.x - 1.0, 2.0 * bary.y, 2.0 * bary.z);
        } else if (bary.y > 0.5) {
            sub = 0u; bary = vec3(2.0 * bary.x, 2.0 * bary.y - 1.0, 2.0 * bary.z);
        } else if (bary.z > 0.5) {
            sub = 1u; bary = vec3(2.0 * bary.x, 2.0 * bary.y, 2.0 * bary.z - 1.0);
        } else {
            // The central triangle is upside down: its corners are the edge midpoints, and the
            // barycentric weight of the midpoint opposite Px is 1 - 2 * bary.x.
            sub = 3u; bary = vec3(1.0) - 2.0 * bary;
        }
        code = (code << 2) | sub;
    }
    return code;
}

uint64_t vpl_sort_key(uint morton, uint normal_code, uint id) {
    return (uint64_t(morton) << (kNormalCodeBits + kIdBits)) | (uint64_t(normal_code) << kIdBits) | uint64_t(id);
}

#endif
