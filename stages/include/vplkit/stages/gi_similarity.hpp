#pragma once
// Geometric similarity's distance for cut blending (hybrid) and interleaved reconstruction
// (rtslc): the thesis eq. 5.3 gives no value. The options' similarity_max_distance is in world
// units; 0 (the default) takes this share of the scene scale (BvhBuffers::scene_scale): blending
// compares a pixel with block representatives up to ~1.5 blocks away, 10-20 pixels at 8 x 8
// blocks, which on a wall seen at a 320-pixel width in Sponza is ~1 unit of its ~30; the normal
// test catches creases either way.

namespace vplkit::stages {

inline constexpr float kGiSimilarityDistanceFraction = 0.1f;

// The distance a stage uses: `option` when > 0, else the scene-relative default.
inline float gi_similarity_distance(float option, float scene_scale) {
    return option > 0.0f ? option : kGiSimilarityDistanceFraction * scene_scale;
}

}  // namespace vplkit::stages
