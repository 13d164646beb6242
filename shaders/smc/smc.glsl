#ifndef VPLKIT_SMC_GLSL
#define VPLKIT_SMC_GLSL

// Sequential Monte Carlo instant radiosity (the SMC paper): the records its stages share.
//
// One SmcVpl is a point y on a surface with what the sampler knows about it: its radiosity B(y)
// (estimated once, from a seed of its own: the SMC paper sec. 3.2.3), its density p(y) by kNN (eq. 7),
// its intensity I(y) = lum(B) / p (eq. 6), and the camera point it is known to be indirectly
// visible from (its mailbox, sec. 3.2.2). The same record holds a ray hit of the candidate pool
// (position = the hit, anchor = the camera point the ray left).

const uint kSmcCovered = 1u;  // the anchor is a camera point (a covered pixel)
const uint kSmcHit = 2u;      // the position is a surface hit
// The surface under the VPL moved away (smc_validate.comp after the geometry moved): it renders
// nothing, no ray revalidates it, and it leaves Y first.
const uint kSmcDead = 4u;
// The VPL's normal is its triangle's winding normal cross(v1 - v0, v2 - v0) negated (the ray that
// found it met the back): smc_follow_surfaces.comp keeps the side when the triangle moves.
const uint kSmcFlipped = 8u;

struct SmcVpl {
    vec3 position;
    uint seed;      // the radiosity estimator's random stream: the same for the VPL's whole life
    vec3 normal;    // unit, the geometric normal on the side the anchor sees
    uint triangle;  // scene triangle of `position` (its diffuse reflectance)
    vec3 radiosity; // B(y), RGB (W/m^2)
    float pdf;      // p(y) (eq. 7) at the last estimate
    vec3 anchor;    // camera point that sees y (mailbox)
    float intensity;  // lum(B) / p (eq. 6) at the last estimate
    vec3 anchor_normal;  // its geometric normal, on the camera's side
    uint flags;     // kSmcCovered | kSmcHit | kSmcDead | kSmcFlipped
    // The radiosity estimate that chose it (as a candidate), which also ranks it while it lives
    // (its intensity, eq. 6). `radiosity` above is a second, independent estimate it renders
    // with: ranked by the estimate it renders with, the VPLs whose estimate came out low would
    // be the first removed and the survivors' light biased high.
    vec3 choice_radiosity;
    uint pad;
    // Where `position` lies on its triangle: the weights of its v1 and v2 (bvh.glsl's BvhHit), so
    // that it moves with the triangle (smc_follow_surfaces.comp).
    vec2 barycentrics;
    uint pad1;
    uint pad2;
};

// What one update counts (the first member persists: the size of the VPL set Y).
struct SmcCounters {
    uint vpl_count;        // |Y|
    uint hit_count;        // camera rays that found a reflecting surface
    uint invalid_count;    // VPLs whose mailbox failed (entries of the invalid list)
    uint revalidated;      // of those, found indirectly visible by the ray casts of sec. 3.2.2
    uint candidate_count;  // |Y^| after resampling
    uint strong_count;     // M_strong (eq. 9)
    uint min_moves;        // M_min (eq. 9)
    uint still_invalid;    // invalid VPLs after revalidation
    uint removed;          // VPLs taken out of Y
    uint move_count;       // candidates put into Y (removed + appended)
    uint cut_short;        // radiosity paths the driver ended early (lavapipe's loop limit)
    uint pad;
};

// Key of a pool entry or candidate that must never be chosen: above every finite float's bits.
const uint kSmcNoKey = 0xffffffffu;

float smc_luminance(vec3 c) {
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

#endif
