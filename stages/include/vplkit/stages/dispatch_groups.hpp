#pragma once
// Whether a generated pipeline can record a dispatch of so many threads, checked when a stage adds
// its step (so a refusal comes before anything is recorded). Pipeline::groups() takes 65,535
// workgroups per dimension, or, for a shader that takes its index from vplkit/dispatch.glsl
// (kFoldsGrid), a 1D grid of up to 65,535 x 65,535 workgroups folded into rows (docs/codegen.md).

#include "vplkit/error.hpp"

#include <cstdint>
#include <stdexcept>
#include <string>

namespace vplkit::stages {

// Throws vplkit::Error("<pass>: shader '<name>': <threads> need <groups> workgroups ...") when
// `pipeline.groups()` refuses the grid.
template <typename Pipeline>
void check_dispatch_groups(const Pipeline& pipeline, const std::string& pass, uint32_t threads_x,
                           uint32_t threads_y = 1, uint32_t threads_z = 1) {
    try {
        (void)pipeline.groups(threads_x, threads_y, threads_z);
    } catch (const std::length_error& e) {
        throw Error(pass + ": " + e.what());
    }
}

}  // namespace vplkit::stages
