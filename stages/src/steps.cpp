// StepList: merge each step's uses per resource, ask the hazard tracker which barriers they
// need, and batch those into one vkCmdPipelineBarrier2 before the step.

#include "vplkit/steps.hpp"

#include "vplkit/barriers.hpp"

#include "hazard_tracker.hpp"
#include "vplkit/error.hpp"

#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace vplkit {
namespace {

constexpr VkAccessFlags2 kShaderRead = VK_ACCESS_2_SHADER_READ_BIT;
constexpr VkAccessFlags2 kShaderWrite = VK_ACCESS_2_SHADER_WRITE_BIT;

struct StageInfo {
    Stage stage;
    const char* name;
    VkPipelineStageFlags2 stages;
    VkAccessFlags2 read;
    VkAccessFlags2 write;  // 0: the stage cannot write
};

constexpr StageInfo kStages[] = {
    {Stage::compute, "compute", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, kShaderRead, kShaderWrite},
    {Stage::vertex, "vertex", VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, kShaderRead, kShaderWrite},
    {Stage::fragment, "fragment", VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, kShaderRead, kShaderWrite},
    {Stage::transfer, "transfer", VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
     VK_ACCESS_2_TRANSFER_WRITE_BIT},
    {Stage::host, "host", VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, VK_ACCESS_2_HOST_WRITE_BIT},
    {Stage::indirect, "indirect", VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, 0},
    {Stage::vertex_input, "vertex input", VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT,
     VK_ACCESS_2_INDEX_READ_BIT | VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, 0},
    {Stage::color_attachment, "color attachment", VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
     VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT},
    {Stage::depth_attachment, "depth attachment",
     VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT},
};

constexpr bool is_shader_stage(Stage s) {
    return s == Stage::compute || s == Stage::vertex || s == Stage::fragment;
}

std::string quoted(const std::string& name) {
    return name.empty() ? "(unnamed)" : "'" + name + "'";
}

VkImageLayout default_layout(Stage stages, Access access) {
    const bool reads = access != Access::write;
    const bool writes = access != Access::read;
    if (stages == Stage::transfer) {
        if (reads && writes) return VK_IMAGE_LAYOUT_GENERAL;
        return writes ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    }
    if (stages == Stage::color_attachment) return VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    if (stages == Stage::depth_attachment) {
        return writes ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL
                      : VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    }
    // Shader access, or a mix of stages: GENERAL is valid for storage and sampled use alike.
    return VK_IMAGE_LAYOUT_GENERAL;
}

// Translates one Use to stage and access bits; throws for combinations that cannot happen.
detail::ResourceAccess translate(const Use& use, const std::string& step) {
    const bool reads = use.access != Access::write;
    const bool writes = use.access != Access::read;
    const std::string resource = (use.is_image() ? "image " : "buffer ") + quoted(use.name());
    if (uint32_t(use.stages) == 0) throw Error("vplkit: pass '" + step + "' uses " + resource + " in no stage");
    detail::ResourceAccess out;
    for (const StageInfo& s : kStages) {
        if (!has_stage(use.stages, s.stage)) continue;
        if (writes && s.write == 0) {
            throw Error("vplkit: pass '" + step + "' writes " + resource + " in the " + s.name +
                        " stage, which only reads");
        }
        if (use.is_image() &&
            (s.stage == Stage::host || s.stage == Stage::indirect || s.stage == Stage::vertex_input)) {
            throw Error("vplkit: pass '" + step + "' uses " + resource + " in the " + s.name +
                        " stage, which takes buffers only");
        }
        if (!use.is_image() && (s.stage == Stage::color_attachment || s.stage == Stage::depth_attachment)) {
            throw Error("vplkit: pass '" + step + "' uses " + resource + " as a " + s.name +
                        ", which takes images only");
        }
        out.stages |= s.stages;
        if (reads)
            out.read |= s.read | (!use.is_image() && is_shader_stage(s.stage) ? VK_ACCESS_2_UNIFORM_READ_BIT : 0);
        if (writes) out.write |= s.write;
    }
    if (use.is_image())
        out.layout = use.layout != VK_IMAGE_LAYOUT_UNDEFINED ? use.layout : default_layout(use.stages, use.access);
    return out;
}

std::string stage_names(VkPipelineStageFlags2 stages) {
    if (stages == VK_PIPELINE_STAGE_2_NONE) return "none";
    std::string out;
    for (const StageInfo& s : kStages) {
        if ((stages & s.stages) == s.stages) out += std::string(out.empty() ? "" : "+") + s.name;
    }
    return out.empty() ? "other" : out;
}

std::string layout_name(VkImageLayout layout) {
    switch (layout) {
        case VK_IMAGE_LAYOUT_UNDEFINED:
            return "UNDEFINED";
        case VK_IMAGE_LAYOUT_GENERAL:
            return "GENERAL";
        case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL:
            return "COLOR_ATTACHMENT_OPTIMAL";
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL:
            return "DEPTH_STENCIL_ATTACHMENT_OPTIMAL";
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL:
            return "DEPTH_STENCIL_READ_ONLY_OPTIMAL";
        case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL:
            return "SHADER_READ_ONLY_OPTIMAL";
        case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL:
            return "TRANSFER_SRC_OPTIMAL";
        case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL:
            return "TRANSFER_DST_OPTIMAL";
        default:
            return "layout " + std::to_string(int(layout));
    }
}

// A step's merged access to one resource.
struct MergedUse {
    const Use* use = nullptr;  // the first use that named the resource
    detail::ResourceAccess access;
    Access kind = Access::read;

    uint64_t key() const {
        return use->is_image() ? uint64_t(reinterpret_cast<uintptr_t>(use->image.image))
                               : uint64_t(reinterpret_cast<uintptr_t>(use->buffer.buffer));
    }
};

Access merged_kind(Access a, Access b) {
    return a == b ? a : Access::read_write;
}

std::vector<MergedUse> merge_uses(const std::vector<Use>& uses, const std::string& step) {
    std::vector<MergedUse> merged;
    for (const Use& use : uses) {
        if (bool(use.buffer) == bool(use.image)) {
            throw Error("vplkit: pass '" + step + "' has a use that names neither exactly one buffer nor one image");
        }
        const detail::ResourceAccess access = translate(use, step);
        MergedUse* target = nullptr;
        for (MergedUse& m : merged) {
            const bool same = use.is_image() ? m.use->is_image() && m.use->image.image == use.image.image
                                             : !m.use->is_image() && m.use->buffer.buffer == use.buffer.buffer;
            if (same) target = &m;
        }
        if (!target) {
            merged.push_back({&use, access, use.access});
            continue;
        }
        if (use.is_image() && target->access.layout != access.layout) {
            throw Error("vplkit: pass '" + step + "' uses image " + quoted(use.name()) + " in two layouts, " +
                        layout_name(target->access.layout) + " and " + layout_name(access.layout));
        }
        target->access.stages |= access.stages;
        target->access.read |= access.read;
        target->access.write |= access.write;
        target->kind = merged_kind(target->kind, use.access);
    }
    return merged;
}

ResourceUse resource_use(const MergedUse& m, const std::string& step, const std::string& name) {
    ResourceUse out;
    out.name = name;
    out.buffer = m.use->is_image() ? VK_NULL_HANDLE : m.use->buffer.buffer;
    out.image = m.use->is_image() ? m.use->image.image : VK_NULL_HANDLE;
    out.step = step;
    out.access = m.kind;
    out.stages = m.access.stages;
    out.access_flags = m.access.read | m.access.write;
    out.layout = m.access.layout;
    out.aspect = m.use->is_image() ? m.use->image.aspect : 0;
    return out;
}

}  // namespace

Use Use::read(const BufferView& buffer, Stage stages) {
    return {buffer, {}, Access::read, stages};
}
Use Use::write(const BufferView& buffer, Stage stages) {
    return {buffer, {}, Access::write, stages};
}
Use Use::read_write(const BufferView& buffer, Stage stages) {
    return {buffer, {}, Access::read_write, stages};
}
Use Use::read(const ImageView& image, Stage stages, VkImageLayout layout) {
    return {{}, image, Access::read, stages, layout};
}
Use Use::write(const ImageView& image, Stage stages, VkImageLayout layout) {
    return {{}, image, Access::write, stages, layout};
}
Use Use::read_write(const ImageView& image, Stage stages, VkImageLayout layout) {
    return {{}, image, Access::read_write, stages, layout};
}

std::string BarrierRecord::describe(const std::vector<std::string>& pass_names) const {
    std::string kinds;
    auto add = [&](uint32_t bit, const char* name) {
        if (hazards & bit) kinds += std::string(kinds.empty() ? "" : "+") + name;
    };
    add(hazard_read_after_write, "RAW");
    add(hazard_write_after_write, "WAW");
    add(hazard_write_after_read, "WAR");
    add(hazard_layout_transition, "layout");
    std::string out = "before " +
                      (pass < pass_names.size() ? quoted(pass_names[pass]) : "pass " + std::to_string(pass)) + ": " +
                      (is_image ? "image " : "buffer ") + quoted(resource) + " " + kinds + " (" +
                      stage_names(src_stages) + " -> " + stage_names(dst_stages);
    if (is_image && old_layout != new_layout) out += ", " + layout_name(old_layout) + " -> " + layout_name(new_layout);
    return out + ")";
}

StepList& StepList::add(std::string name, std::vector<Use> uses, Record record) {
    if (!record) throw Error("vplkit: pass '" + name + "' has no recording function");
    // Validate now, where the caller's mistake is, rather than at recording.
    merge_uses(uses, name);
    for (const Use& use : uses) {
        if (use.binding_name) continue;
        if (use.is_image()) {
            this->name(use.image);
        } else {
            this->name(use.buffer);
        }
    }
    steps_.push_back({std::move(name), std::move(uses), std::move(record), tag_});
    return *this;
}

void StepList::name(const BufferView& view) {
    if (view && !view.name.empty()) buffer_names_.emplace(view.buffer, view.name);
}

void StepList::name(const ImageView& view) {
    if (view && !view.name.empty()) image_names_.emplace(view.image, view.name);
}

const std::string& StepList::name_of(const Use& use) const {
    if (use.is_image()) {
        const auto it = image_names_.find(use.image.image);
        return it != image_names_.end() ? it->second : use.name();
    }
    const auto it = buffer_names_.find(use.buffer.buffer);
    return it != buffer_names_.end() ? it->second : use.name();
}

std::vector<ResourceUse> StepList::entry() const {
    std::vector<ResourceUse> out;
    std::map<uint64_t, bool> seen;
    for (const Step& step : steps_) {
        for (const MergedUse& m : merge_uses(step.uses, step.name)) {
            if (seen.emplace(m.key(), true).second) out.push_back(resource_use(m, step.name, name_of(*m.use)));
        }
    }
    return out;
}

std::vector<ResourceUse> StepList::exit() const {
    std::vector<ResourceUse> out;
    std::map<uint64_t, size_t> index;
    for (const Step& step : steps_) {
        for (const MergedUse& m : merge_uses(step.uses, step.name)) {
            const auto [it, inserted] = index.emplace(m.key(), out.size());
            if (inserted) {
                out.push_back(resource_use(m, step.name, name_of(*m.use)));
            } else {
                out[it->second] = resource_use(m, step.name, name_of(*m.use));
            }
        }
    }
    return out;
}

std::vector<BarrierRecord> StepList::record(VkCommandBuffer cmd) const {
    return record(cmd, Hooks{});
}

std::vector<BarrierRecord> StepList::record(VkCommandBuffer cmd, const Hooks& hooks) const {
    std::vector<std::vector<MergedUse>> merged;
    for (const Step& step : steps_) merged.push_back(merge_uses(step.uses, step.name));

    // An image with a layout pointer starts from it; one without, from its first use's layout.
    // Layouts move as barriers are recorded (a step's record function may read them); if
    // recording fails they go back.
    std::map<VkBuffer, detail::ResourceState> buffer_states;
    std::map<VkImage, detail::ResourceState> image_states;
    std::vector<std::pair<VkImageLayout*, VkImageLayout>> saved_layouts;
    for (const auto& uses : merged) {
        for (const MergedUse& m : uses) {
            if (!m.use->is_image() || image_states.count(m.use->image.image)) continue;
            VkImageLayout* layout = m.use->image.layout;
            image_states[m.use->image.image].layout = layout ? *layout : m.access.layout;
            if (layout) saved_layouts.emplace_back(layout, *layout);
        }
    }

    std::vector<BarrierRecord> barriers;
    try {
        for (size_t i = 0; i < steps_.size(); ++i) {
            const Step& step = steps_[i];
            if (hooks.before) hooks.before(cmd, i);
            std::vector<VkBufferMemoryBarrier2> buffer_barriers;
            std::vector<VkImageMemoryBarrier2> image_barriers;
            for (const MergedUse& m : merged[i]) {
                const Use& use = *m.use;
                detail::ResourceState& state =
                    use.is_image() ? image_states[use.image.image] : buffer_states[use.buffer.buffer];
                const detail::BarrierNeed need = detail::track_access(state, m.access, use.is_image());
                if (!need.hazards) continue;
                BarrierRecord record;
                record.pass = i;
                record.resource = name_of(use);
                record.is_image = use.is_image();
                record.hazards = need.hazards;
                record.src_stages = need.src_stages;
                record.src_access = need.src_access;
                record.dst_stages = need.dst_stages;
                record.dst_access = need.dst_access;
                record.old_layout = need.old_layout;
                record.new_layout = need.new_layout;
                barriers.push_back(record);
                if (!use.is_image()) {
                    VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
                    b.srcStageMask = need.src_stages;
                    b.srcAccessMask = need.src_access;
                    b.dstStageMask = need.dst_stages;
                    b.dstAccessMask = need.dst_access;
                    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
                    b.buffer = use.buffer.buffer;
                    b.offset = 0;
                    b.size = VK_WHOLE_SIZE;
                    buffer_barriers.push_back(b);
                } else {
                    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
                    b.srcStageMask = need.src_stages;
                    b.srcAccessMask = need.src_access;
                    b.dstStageMask = need.dst_stages;
                    b.dstAccessMask = need.dst_access;
                    b.oldLayout = need.old_layout;
                    b.newLayout = need.new_layout;
                    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
                    b.image = use.image.image;
                    b.subresourceRange = {use.image.aspect, 0, 1, 0, 1};
                    image_barriers.push_back(b);
                    if (use.image.layout) *use.image.layout = need.new_layout;
                }
            }
            pipeline_barriers(cmd, buffer_barriers, image_barriers);
            try {
                step.record(cmd);
            } catch (const std::length_error& e) {
                // A generated Pipeline::groups() refusing a grid no device must take: name the step.
                throw Error("step '" + step.name + "': " + e.what());
            }
            if (hooks.after) hooks.after(cmd, i);
        }
    } catch (...) {
        for (auto& [layout, value] : saved_layouts) *layout = value;
        throw;
    }
    return barriers;
}

}  // namespace vplkit
