#pragma once
// What the whole-frame tests share (test_render*.cpp): the Cornell box with a point light, and the
// check that a frame's parts add up.

#include "vplkit/renderer.hpp"

#include <doctest/doctest.h>

#include <cstddef>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace vplkit::render_test {

inline constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";

// Checks that the composed radiance is direct + indirect, exactly (one float addition), with
// non-negative indirect light; returns how many channels have indirect light and no direct light.
inline size_t check_parts_add_up(const vplkit::RenderedImage& image) {
    size_t indirect_only = 0;
    for (size_t i = 0; i < image.radiance.size(); ++i) {
        CHECK(image.radiance[i] == image.direct[i] + image.indirect[i]);
        CHECK(image.indirect[i] >= 0.0f);
        if (image.direct[i] == 0.0f && image.indirect[i] > 0.0f) ++indirect_only;
    }
    return indirect_only;
}

}  // namespace vplkit::render_test
