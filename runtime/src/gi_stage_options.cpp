#include "gi_stage_options.hpp"

namespace vplkit {

GiStageOptions gi_stage_options(const RenderSettings& settings, float similarity_distance) {
    GiStageOptions o;
    o.sst.samples_per_pixel = settings.samples_per_pixel;
    o.sst.seed = settings.seed;
    o.sst.frame = settings.frame;
    o.rtslc.samples_per_pixel = settings.samples_per_pixel;
    o.rtslc.block_size = settings.block_size;
    o.rtslc.interleave = settings.interleave;
    o.rtslc.frame = settings.frame;
    o.rtslc.seed = settings.seed;
    o.rtslc.similarity_max_distance = similarity_distance;
    o.hybrid.samples_per_pixel = settings.samples_per_pixel;
    o.hybrid.block_size = settings.block_size;
    o.hybrid.seed = settings.seed;
    o.hybrid.frame = settings.frame;
    o.hybrid.similarity_max_distance = similarity_distance;
    o.hybrid.mock_cuts = settings.mock_cuts;
    o.hybrid.traversal = settings.hybrid_traversal;
    return o;
}

}  // namespace vplkit
