#pragma once
// The sampling methods' stage options from a frame's settings: what the renderer records with
// (renderer_gi.cpp) and what their rows in the method table check (gi_methods.cpp).

#include "vplkit/render_settings.hpp"
#include "vplkit/stages/hybrid_gi.hpp"
#include "vplkit/stages/rtslc.hpp"
#include "vplkit/stages/sst_gi.hpp"

namespace vplkit {

struct GiStageOptions {
    stages::SstGiOptions sst;
    stages::RtslcOptions rtslc;
    stages::HybridOptions hybrid;
};

// similarity_distance in world units (any positive value to check the options alone).
GiStageOptions gi_stage_options(const RenderSettings& settings, float similarity_distance);

}  // namespace vplkit
