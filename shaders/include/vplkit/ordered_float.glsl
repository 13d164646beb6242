#ifndef VPLKIT_ORDERED_FLOAT_GLSL
#define VPLKIT_ORDERED_FLOAT_GLSL

// Maps a float to a uint whose unsigned order equals the float order (-inf < ... < -0 < +0 < ... < +inf),
// so bounds can be reduced with integer atomicMin/atomicMax on every device: float atomic
// min/max is an optional feature.
uint float_to_ordered(float f) {
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}

float ordered_to_float(uint u) {
    return uintBitsToFloat((u & 0x80000000u) != 0u ? (u & 0x7fffffffu) : ~u);
}

#endif
