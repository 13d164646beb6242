#pragma once
// Private: the raster stages' graphics pipelines, created once per context through the context's
// pipeline cache (Context::pipeline), like the generated compute pipelines. A GraphicsPipeline
// needs the Context itself, not only the VkDevice that the cache's create() hook receives, so
// the Spec carries it; it also keys the cache, which is per context anyway.

#include "vplkit/context.hpp"
#include "vplkit/graphics_pipeline.hpp"

#include <vulkan/vulkan.h>

namespace vplkit::detail {

// Describe::name() names the pipeline; Describe::state() gives its RasterState.
template <class VS, class FS, class Describe>
struct CachedRasterPipeline {
  struct Spec {
    Context* context = nullptr;
  };

  GraphicsPipeline pipeline;

  static VkResult create(VkDevice, VkPipelineCache, const Spec& spec, CachedRasterPipeline* out) {
    out->pipeline = GraphicsPipeline::create<VS, FS>(*spec.context, Describe::state(), Describe::name());
    return VK_SUCCESS;
  }
  void destroy() { pipeline = GraphicsPipeline(); }

  static const GraphicsPipeline& get(Context& context) {
    return context.pipeline<CachedRasterPipeline>(Spec{&context}).pipeline;
  }
};

}  // namespace vplkit::detail
