#ifndef VPLKIT_BITONIC_GLSL
#define VPLKIT_BITONIC_GLSL

// Index pairs of the bitonic sorting network in its all-ascending form: the first step of each
// stage compares mirrored positions in a block of `block` elements ("flip"), the later steps compare
// elements `distance` apart ("half-cleaner"). Every comparison puts the smaller key at the lower index.
// So the array can be padded virtually to a power of two with +infinity keys: a pair whose upper
// index lies past the end never swaps, and the padding is never stored.
// `block` and `distance` are powers of two; `pair` is the pair's number within the whole step.

uvec2 bitonic_flip_pair(uint pair, uint block) {
    uint half_block = block >> 1;
    uint base = (pair / half_block) * block;
    uint offset = pair & (half_block - 1u);
    return uvec2(base + offset, base + block - 1u - offset);
}

uvec2 bitonic_half_cleaner_pair(uint pair, uint distance) {
    uint lower = (pair / distance) * (2u * distance) + (pair & (distance - 1u));
    return uvec2(lower, lower + distance);
}

#endif
