#pragma once
// StepList: what a stage records, as a list of steps (a dispatch, a fill, a draw), each with the
// buffers and images it touches and how. A stage function appends its steps; the caller then
//   - records them into its own command buffer: steps.record(cmd) inserts a synchronization2
//     barrier before a step only where a use conflicts with an earlier one (read-after-write,
//     write-after-write, write-after-read, an image layout change); record_with_caller_barriers
//     adds a barrier on each side from and to all of the caller's own commands;
//   - or hands them to its own frame graph: steps.steps() (name, uses, record function) and
//     entry() / exit(): the first and last access of each resource, what the caller must make
//     visible before the stage and what later work must wait for.
//
//   vplkit::StepList steps;
//   vplkit::stages::add_sst_passes(device, steps, leaves, nodes, counters, count);
//   steps.record(cmd);
//
// Resources are tracked whole (no sub-ranges), by handle. vplkit::PassList (the runtime's
// convenience layer) is a StepList that also submits and times each step.

#include "vplkit/views.hpp"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

namespace vplkit {

// Where a step touches a resource. Combine with | when one step uses it in several stages.
enum class Stage : uint32_t {
    compute = 1u << 0,
    vertex = 1u << 1,
    fragment = 1u << 2,
    transfer = 1u << 3,      // copies, fills, clears, blits
    host = 1u << 4,          // the CPU reads it after the submission
    indirect = 1u << 5,      // indirect dispatch/draw arguments
    vertex_input = 1u << 6,  // vertex and index buffers
    color_attachment = 1u << 7,
    depth_attachment = 1u << 8,  // depth/stencil tests and writes
};
constexpr Stage operator|(Stage a, Stage b) {
    return Stage(uint32_t(a) | uint32_t(b));
}
constexpr bool has_stage(Stage set, Stage s) {
    return (uint32_t(set) & uint32_t(s)) != 0;
}

enum class Access { read, write, read_write };

struct Use {
    BufferView buffer;  // exactly one of buffer and image is set
    ImageView image;
    Access access = Access::read;
    Stage stages = Stage::compute;
    // For images: the layout the step needs. VK_IMAGE_LAYOUT_UNDEFINED = the default for the
    // stage and access: GENERAL for shader access (valid for both storage and sampled images),
    // TRANSFER_SRC/DST_OPTIMAL for transfer reads/writes, the attachment layouts for attachments.
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    // The name is the shader binding's ("order", "nodes"), not the caller's view's: set by
    // binding_uses, whose descriptors carry no name. StepList reports such a resource under the
    // caller's name when one is known (see StepList::name).
    bool binding_name = false;

    bool is_image() const { return bool(image); }
    const std::string& name() const { return is_image() ? image.name : buffer.name; }

    static Use read(const BufferView& buffer, Stage stages = Stage::compute);
    static Use write(const BufferView& buffer, Stage stages = Stage::compute);
    static Use read_write(const BufferView& buffer, Stage stages = Stage::compute);
    static Use transfer_src(const BufferView& buffer) { return read(buffer, Stage::transfer); }
    static Use transfer_dst(const BufferView& buffer) { return write(buffer, Stage::transfer); }
    static Use indirect(const BufferView& buffer) { return read(buffer, Stage::indirect); }
    // The host reads the buffer once the submission has finished (a mapped readback buffer).
    static Use host_read(const BufferView& buffer) { return read(buffer, Stage::host); }

    static Use read(const ImageView& image, Stage stages = Stage::compute,
                    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED);
    static Use write(const ImageView& image, Stage stages = Stage::compute,
                     VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED);
    static Use read_write(const ImageView& image, Stage stages = Stage::compute,
                          VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED);
    // Sampled through a combined image sampler / sampled image in SHADER_READ_ONLY_OPTIMAL.
    static Use sampled(const ImageView& image, Stage stages = Stage::fragment) {
        return read(image, stages, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }
    static Use transfer_src(const ImageView& image) { return read(image, Stage::transfer); }
    static Use transfer_dst(const ImageView& image) { return write(image, Stage::transfer); }
    static Use color_attachment(const ImageView& image) { return read_write(image, Stage::color_attachment); }
    static Use depth_attachment(const ImageView& image) { return read_write(image, Stage::depth_attachment); }
};

// Why a barrier was inserted (bit set).
enum Hazard : uint32_t {
    hazard_read_after_write = 1u << 0,
    hazard_write_after_write = 1u << 1,
    hazard_write_after_read = 1u << 2,
    hazard_layout_transition = 1u << 3,
};

// One buffer or image barrier that recording inserted.
struct BarrierRecord {
    size_t pass = 0;       // index of the step it was recorded before
    std::string resource;  // the buffer's or image's name (see StepList::name; "" when unnamed)
    bool is_image = false;
    uint32_t hazards = 0;  // Hazard bits
    VkPipelineStageFlags2 src_stages = 0;
    VkAccessFlags2 src_access = 0;
    VkPipelineStageFlags2 dst_stages = 0;
    VkAccessFlags2 dst_access = 0;
    VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImageLayout new_layout = VK_IMAGE_LAYOUT_UNDEFINED;

    // "before 'sort': keys RAW (compute write -> compute read)"
    std::string describe(const std::vector<std::string>& pass_names) const;
};

// One resource's access as Vulkan sees it: what the caller's barrier before a stage must make
// visible to (entry), or what work after it must wait for (exit).
struct ResourceUse {
    std::string name;                  // the caller's view name (see StepList::name)
    VkBuffer buffer = VK_NULL_HANDLE;  // one of buffer and image
    VkImage image = VK_NULL_HANDLE;
    std::string step;              // the first (entry) or last (exit) step that uses it
    Access access = Access::read;  // of that step
    VkPipelineStageFlags2 stages = 0;
    VkAccessFlags2 access_flags = 0;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // images: the layout that step uses
    VkImageAspectFlags aspect = 0;                     // images: the view's (DEPTH_BIT for a depth image)
};

struct Step {
    using Record = std::function<void(VkCommandBuffer)>;
    std::string name;
    std::vector<Use> uses;
    Record record;
    uint32_t tag = 0;  // the caller's label for the step's group (StepList::set_tag); 0 = none
};

class StepList {
public:
    using Record = Step::Record;

    virtual ~StepList() = default;

    // Appends a step. `uses` lists every buffer and image the step reads or writes; a resource
    // may appear several times (the uses are merged), but an image must not be asked for in two
    // different layouts in one step (Error). The record function runs when the list is recorded;
    // what it captures must live until then.
    StepList& add(std::string name, std::vector<Use> uses, Record record);

    // Names a caller's buffer or image for entry(), exit() and the barrier records. A step built
    // from a shader's bindings (binding_uses) knows only the binding names ("order", "nodes",
    // "counters"), so each stage function names the views it was handed here; a use added with a
    // caller's view (Use::read(view), an image matched by binding_uses) names its resource too.
    // The reported name is always the caller's view name (the first one given for a handle); only
    // a resource whose views all have an empty name is reported under its binding name.
    void name(const BufferView& view);
    void name(const ImageView& view);
    void names(std::initializer_list<BufferView> views) {
        for (const BufferView& view : views) name(view);
    }
    // The name entry(), exit() and record() report for `use`'s resource.
    const std::string& name_of(const Use& use) const;

    // Records every step into `cmd`, in order, with the barriers between them. Images whose
    // view carries a layout pointer are transitioned from it (and it is updated). The command
    // buffer must be in the recording state and allow compute (and, for raster steps, graphics).
    // Returns the barriers it inserted. Can be called again (e.g. into another command buffer).
    std::vector<BarrierRecord> record(VkCommandBuffer cmd) const;

    // The first / last use of each resource, in order of first appearance.
    std::vector<ResourceUse> entry() const;
    std::vector<ResourceUse> exit() const;

    // record() between two barriers in the caller's terms, for a caller without a frame graph:
    // before the steps, from all of the caller's earlier commands (`caller_stages`, their writes)
    // to each resource's first use (entry()); after them, from each resource's last use (exit())
    // to the caller's later commands (their reads and writes). An image whose view has a layout
    // pointer moves from that layout to its first use's in the first barrier; hand the kit any
    // other image in its first use's layout. Each image is left in its last use's layout.
    std::vector<BarrierRecord> record_with_caller_barriers(
        VkCommandBuffer cmd, VkPipelineStageFlags2 caller_stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT) const;

    // Tags every step added from now on (a frame graph's id for the stage that adds them, so that
    // steps are grouped by a value rather than by their names). 0 = untagged, the default.
    void set_tag(uint32_t tag) { tag_ = tag; }
    uint32_t tag() const { return tag_; }

    const std::vector<Step>& steps() const { return steps_; }
    size_t size() const { return steps_.size(); }
    bool empty() const { return steps_.empty(); }
    virtual void clear() {
        steps_.clear();
        buffer_names_.clear();
        image_names_.clear();
        tag_ = 0;
    }

    // Hooks around each step, for a recorder that labels or times them (PassList does both).
    struct Hooks {
        std::function<void(VkCommandBuffer, size_t step)> before;  // before the step's barriers
        std::function<void(VkCommandBuffer, size_t step)> after;   // after its commands
    };
    std::vector<BarrierRecord> record(VkCommandBuffer cmd, const Hooks& hooks) const;

private:
    std::vector<Step> steps_;
    std::map<VkBuffer, std::string> buffer_names_;  // the caller's names, by handle
    std::map<VkImage, std::string> image_names_;
    uint32_t tag_ = 0;
};

}  // namespace vplkit
