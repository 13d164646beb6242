#pragma once
// A step's uses, derived from the shader's reflection rather than written a second time: every
// binding of a generated Bindings (vplkit/shaders/<name>.hpp) becomes a Use with the access the
// SPIR-V declares (kBindingAccess: readonly -> read, writeonly -> write, else read and write).
// Buffers come from the descriptors themselves; an image binding names only a VkImageView, so
// the images the bindings use are passed in and matched by view. A buffer's use carries the
// binding's name ("order"), marked Use::binding_name: StepList reports the caller's view name
// instead once the stage function has named the view (StepList::name); images carry the
// caller's ImageView, name included.
//
//   shaders::build_sst::Bindings b;
//   b.leaves = leaves.descriptor(); ...
//   passes.add("build sst", binding_uses<shaders::build_sst::Module>(b), [&pipeline, b, push](VkCommandBuffer cmd) {
//       pipeline.dispatch(cmd, b, push, threads);
//   });

#include "vplkit/error.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/steps.hpp"

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

namespace vplkit::stages {

inline Access access_of(shaders::Access access) {
    switch (access) {
        case shaders::Access::read:
            return Access::read;
        case shaders::Access::write:
            return Access::write;
        case shaders::Access::read_write:
            break;
    }
    return Access::read_write;
}

// The uses of one dispatch of Module (a generated shader's Module type) with `bindings`, in
// `stage`. Throws Error when an image binding's view is not among `images`. Array elements left
// empty (VK_NULL_HANDLE) are skipped.
template <class Module>
std::vector<Use> binding_uses(const typename Module::Bindings& bindings, const std::vector<ImageView>& images = {},
                              Stage stage = Stage::compute) {
    std::vector<Use> uses;
    constexpr uint32_t count = Module::set_layout_binding_count;
    if constexpr (count > 0) {
        VkWriteDescriptorSet writes[count];
        Module::write_descriptors(bindings, writes);
        for (uint32_t i = 0; i < count; ++i) {
            const Access access = access_of(Module::binding_access[i]);
            const std::string name = Module::binding_names[i];
            for (uint32_t e = 0; e < writes[i].descriptorCount; ++e) {
                if (writes[i].pBufferInfo != nullptr) {
                    const VkDescriptorBufferInfo& info = writes[i].pBufferInfo[e];
                    if (info.buffer == VK_NULL_HANDLE) continue;
                    // A descriptor carries no name: the binding's stands in until the stage
                    // function names the caller's view (StepList::name).
                    Use use{BufferView{info.buffer, info.offset, info.range, name}, {}, access, stage};
                    use.binding_name = true;
                    uses.push_back(use);
                    continue;
                }
                const VkDescriptorImageInfo& info = writes[i].pImageInfo[e];
                if (info.imageView == VK_NULL_HANDLE) continue;
                const ImageView* image = nullptr;
                for (const ImageView& candidate : images) {
                    if (candidate.view == info.imageView) image = &candidate;
                }
                if (image == nullptr) {
                    throw Error("vplkit: binding '" + name +
                                "' uses an image view that is not among the step's images");
                }
                // Read-only sampled images stay in their layout; storage access needs GENERAL.
                uses.push_back({{}, *image, access, stage, info.imageLayout});
            }
        }
    }
    return uses;
}

// The threads of one dispatch: a count (x), or an image's width by height ({x, y}).
struct DispatchThreads {
    DispatchThreads(uint32_t x_, uint32_t y_ = 1, uint32_t z_ = 1) : x(x_), y(y_), z(z_) {}  // implicit: a count is x
    uint32_t x;
    uint32_t y;
    uint32_t z;
};

// One dispatch of Module's `pipeline` over `threads` threads as a step, its uses from the
// bindings (the shape every compute step of the kit has). The push constants are computed by
// the caller and captured by value:
//   add_dispatch<shaders::smc_vpls::Module>(passes, "smc vpls", pipeline, b, push, budget);
//   add_dispatch<shaders::tonemap::Module>(passes, "tonemap", pipeline, b, push, {hdr.width, hdr.height}, {hdr, ldr});
template <class Module, class Pipeline>
void add_dispatch(StepList& passes, std::string name, const Pipeline& pipeline,
                  const typename Module::Bindings& bindings, const typename Pipeline::Push& push,
                  DispatchThreads threads, const std::vector<ImageView>& images = {}) {
    passes.add(std::move(name), binding_uses<Module>(bindings, images),
               [&pipeline, bindings, push, threads](VkCommandBuffer cmd) {
                   pipeline.dispatch(cmd, bindings, push, threads.x, threads.y, threads.z);
               });
}

// A generated Pipeline of a shader without push constants (it declares no Push).
template <class Pipeline>
concept PipelineWithoutPush = !requires {
    typename Pipeline::Push;
};

// The same for a shader without push constants.
template <class Module, PipelineWithoutPush Pipeline>
void add_dispatch(StepList& passes, std::string name, const Pipeline& pipeline,
                  const typename Module::Bindings& bindings, DispatchThreads threads,
                  const std::vector<ImageView>& images = {}) {
    passes.add(std::move(name), binding_uses<Module>(bindings, images),
               [&pipeline, bindings, threads](VkCommandBuffer cmd) {
                   pipeline.dispatch(cmd, bindings, threads.x, threads.y, threads.z);
               });
}

// The same with the uses written by the caller (steps whose uses are not derived from the
// bindings yet; deriving them would change the barriers recorded).
template <class Pipeline>
void add_dispatch(StepList& passes, std::string name, std::vector<Use> uses, const Pipeline& pipeline,
                  const typename Pipeline::Bindings& bindings, const typename Pipeline::Push& push,
                  DispatchThreads threads) {
    passes.add(std::move(name), std::move(uses), [&pipeline, bindings, push, threads](VkCommandBuffer cmd) {
        pipeline.dispatch(cmd, bindings, push, threads.x, threads.y, threads.z);
    });
}

// The same for a shader without push constants.
template <PipelineWithoutPush Pipeline>
void add_dispatch(StepList& passes, std::string name, std::vector<Use> uses, const Pipeline& pipeline,
                  const typename Pipeline::Bindings& bindings, DispatchThreads threads) {
    passes.add(std::move(name), std::move(uses), [&pipeline, bindings, threads](VkCommandBuffer cmd) {
        pipeline.dispatch(cmd, bindings, threads.x, threads.y, threads.z);
    });
}

}  // namespace vplkit::stages
