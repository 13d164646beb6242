// PassList::run: merge each pass's uses per resource, ask the hazard tracker which barriers
// they need, batch those into one vkCmdPipelineBarrier2 before the pass, and bracket the pass
// with a debug label and two timestamps.

#include "vplkit/pass_list.hpp"

#include "hazard_tracker.hpp"
#include "timestamps.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"

#include <map>
#include <numeric>
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

constexpr bool is_shader_stage(Stage s) { return s == Stage::compute || s == Stage::vertex || s == Stage::fragment; }

std::string quoted(const std::string& name) { return name.empty() ? "(unnamed)" : "'" + name + "'"; }

VkImageLayout default_layout(Stage stages, Access access) {
  const bool reads = access != Access::write;
  const bool writes = access != Access::read;
  if (stages == Stage::transfer) {
    if (reads && writes) return VK_IMAGE_LAYOUT_GENERAL;
    return writes ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  }
  if (stages == Stage::color_attachment) return VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  if (stages == Stage::depth_attachment) {
    return writes ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  }
  // Shader access, or a mix of stages: GENERAL is valid for storage and sampled use alike.
  return VK_IMAGE_LAYOUT_GENERAL;
}

// Translates one Use to stage and access bits; throws for combinations that cannot happen.
detail::ResourceAccess translate(const Use& use, const std::string& pass) {
  const bool reads = use.access != Access::write;
  const bool writes = use.access != Access::read;
  const std::string resource = use.buffer ? "buffer " + quoted(use.buffer->name()) : "image " + quoted(use.image->name());
  if (uint32_t(use.stages) == 0) throw Error("vplkit: pass '" + pass + "' uses " + resource + " in no stage");
  detail::ResourceAccess out;
  for (const StageInfo& s : kStages) {
    if (!has_stage(use.stages, s.stage)) continue;
    if (writes && s.write == 0) {
      throw Error("vplkit: pass '" + pass + "' writes " + resource + " in the " + s.name + " stage, which only reads");
    }
    if (use.image && (s.stage == Stage::host || s.stage == Stage::indirect || s.stage == Stage::vertex_input)) {
      throw Error("vplkit: pass '" + pass + "' uses " + resource + " in the " + s.name + " stage, which takes buffers only");
    }
    if (use.buffer && (s.stage == Stage::color_attachment || s.stage == Stage::depth_attachment)) {
      throw Error("vplkit: pass '" + pass + "' uses " + resource + " as a " + s.name + ", which takes images only");
    }
    out.stages |= s.stages;
    if (reads) out.read |= s.read | (use.buffer && is_shader_stage(s.stage) ? VK_ACCESS_2_UNIFORM_READ_BIT : 0);
    if (writes) out.write |= s.write;
  }
  if (use.image) out.layout = use.layout != VK_IMAGE_LAYOUT_UNDEFINED ? use.layout : default_layout(use.stages, use.access);
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
    case VK_IMAGE_LAYOUT_UNDEFINED: return "UNDEFINED";
    case VK_IMAGE_LAYOUT_GENERAL: return "GENERAL";
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return "COLOR_ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL: return "DEPTH_STENCIL_ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL: return "DEPTH_STENCIL_READ_ONLY_OPTIMAL";
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return "SHADER_READ_ONLY_OPTIMAL";
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "TRANSFER_SRC_OPTIMAL";
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "TRANSFER_DST_OPTIMAL";
    default: return "layout " + std::to_string(int(layout));
  }
}

struct MergedUse {
  const Buffer* buffer = nullptr;
  Image* image = nullptr;
  detail::ResourceAccess access;
};

std::vector<MergedUse> merge_uses(const std::vector<Use>& uses, const std::string& pass) {
  std::vector<MergedUse> merged;
  for (const Use& use : uses) {
    if ((use.buffer == nullptr) == (use.image == nullptr)) {
      throw Error("vplkit: pass '" + pass + "' has a use that names neither exactly one buffer nor one image");
    }
    if (use.buffer && !*use.buffer) throw Error("vplkit: pass '" + pass + "' uses an empty buffer");
    if (use.image && !*use.image) throw Error("vplkit: pass '" + pass + "' uses an empty image");
    const detail::ResourceAccess access = translate(use, pass);
    MergedUse* target = nullptr;
    for (MergedUse& m : merged) {
      if ((use.buffer && m.buffer && m.buffer->handle() == use.buffer->handle()) || (use.image && m.image == use.image)) {
        target = &m;
      }
    }
    if (!target) {
      merged.push_back({use.buffer, use.image, access});
      continue;
    }
    if (use.image && target->access.layout != access.layout) {
      throw Error("vplkit: pass '" + pass + "' uses image " + quoted(use.image->name()) + " in two layouts, " +
                  layout_name(target->access.layout) + " and " + layout_name(access.layout));
    }
    target->access.stages |= access.stages;
    target->access.read |= access.read;
    target->access.write |= access.write;
  }
  return merged;
}

}  // namespace

Use Use::read(const Buffer& buffer, Stage stages) { return {&buffer, nullptr, Access::read, stages}; }
Use Use::write(const Buffer& buffer, Stage stages) { return {&buffer, nullptr, Access::write, stages}; }
Use Use::read_write(const Buffer& buffer, Stage stages) { return {&buffer, nullptr, Access::read_write, stages}; }
Use Use::read(Image& image, Stage stages, VkImageLayout layout) { return {nullptr, &image, Access::read, stages, layout}; }
Use Use::write(Image& image, Stage stages, VkImageLayout layout) { return {nullptr, &image, Access::write, stages, layout}; }
Use Use::read_write(Image& image, Stage stages, VkImageLayout layout) {
  return {nullptr, &image, Access::read_write, stages, layout};
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
  std::string out = "before " + (pass < pass_names.size() ? quoted(pass_names[pass]) : "pass " + std::to_string(pass)) +
                    ": " + (is_image ? "image " : "buffer ") + quoted(resource) + " " + kinds + " (" +
                    stage_names(src_stages) + " -> " + stage_names(dst_stages);
  if (is_image && old_layout != new_layout) out += ", " + layout_name(old_layout) + " -> " + layout_name(new_layout);
  return out + ")";
}

PassList& PassList::add(std::string name, std::vector<Use> uses, Record record) {
  if (!record) throw Error("vplkit: pass '" + name + "' has no recording function");
  // Validate now, where the caller's mistake is, rather than at run().
  merge_uses(uses, name);
  passes_.push_back({std::move(name), std::move(uses), std::move(record)});
  return *this;
}

void PassList::clear() {
  passes_.clear();
  timings_.clear();
  barriers_.clear();
  pipeline_barrier_calls_ = 0;
}

double PassList::total_gpu_ms() const {
  return std::accumulate(timings_.begin(), timings_.end(), 0.0,
                         [](double sum, const PassTiming& t) { return sum + t.gpu_ms; });
}

std::string PassList::describe_barriers() const {
  std::vector<std::string> names;
  for (const Pass& p : passes_) names.push_back(p.name);
  std::string out;
  for (const BarrierRecord& b : barriers_) out += b.describe(names) + "\n";
  return out;
}

void PassList::run(Context& context) {
  timings_.clear();
  barriers_.clear();
  pipeline_barrier_calls_ = 0;
  if (passes_.empty()) return;

  std::vector<std::vector<MergedUse>> merged;
  for (const Pass& pass : passes_) merged.push_back(merge_uses(pass.uses, pass.name));

  // Layouts move as barriers are recorded (so a pass's callback can read image.layout() for its
  // descriptors); if recording fails they go back, since nothing was submitted.
  std::vector<std::pair<Image*, VkImageLayout>> saved_layouts;
  std::map<VkBuffer, detail::ResourceState> buffer_states;
  std::map<Image*, detail::ResourceState> image_states;
  for (const auto& uses : merged) {
    for (const MergedUse& m : uses) {
      if (m.image && !image_states.count(m.image)) {
        image_states[m.image].layout = m.image->layout();
        saved_layouts.emplace_back(m.image, m.image->layout());
      }
    }
  }

  detail::TimestampQueries queries(context, uint32_t(2 * passes_.size()));
  std::vector<BarrierRecord> barriers;
  size_t calls = 0;
  try {
    context.one_shot([&](VkCommandBuffer cmd) {
      queries.reset(cmd);
      context.begin_label(cmd, name_);
      for (size_t i = 0; i < passes_.size(); ++i) {
        const Pass& pass = passes_[i];
        context.begin_label(cmd, pass.name);
        queries.write(cmd, uint32_t(2 * i));

        std::vector<VkBufferMemoryBarrier2> buffer_barriers;
        std::vector<VkImageMemoryBarrier2> image_barriers;
        for (const MergedUse& m : merged[i]) {
          detail::ResourceState& state = m.buffer ? buffer_states[m.buffer->handle()] : image_states[m.image];
          const detail::BarrierNeed need = detail::track_access(state, m.access, m.image != nullptr);
          if (!need.hazards) continue;
          BarrierRecord record;
          record.pass = i;
          record.resource = m.buffer ? m.buffer->name() : m.image->name();
          record.is_image = m.image != nullptr;
          record.hazards = need.hazards;
          record.src_stages = need.src_stages;
          record.src_access = need.src_access;
          record.dst_stages = need.dst_stages;
          record.dst_access = need.dst_access;
          record.old_layout = need.old_layout;
          record.new_layout = need.new_layout;
          barriers.push_back(record);
          if (m.buffer) {
            VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
            b.srcStageMask = need.src_stages;
            b.srcAccessMask = need.src_access;
            b.dstStageMask = need.dst_stages;
            b.dstAccessMask = need.dst_access;
            b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.buffer = m.buffer->handle();
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
            b.image = m.image->handle();
            b.subresourceRange = {m.image->aspect(), 0, 1, 0, 1};
            image_barriers.push_back(b);
            m.image->set_layout(need.new_layout);
          }
        }
        if (!buffer_barriers.empty() || !image_barriers.empty()) {
          VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
          dependency.bufferMemoryBarrierCount = uint32_t(buffer_barriers.size());
          dependency.pBufferMemoryBarriers = buffer_barriers.data();
          dependency.imageMemoryBarrierCount = uint32_t(image_barriers.size());
          dependency.pImageMemoryBarriers = image_barriers.data();
          vkCmdPipelineBarrier2(cmd, &dependency);
          ++calls;
        }

        pass.record(cmd);
        queries.write(cmd, uint32_t(2 * i + 1));
        context.end_label(cmd);
      }
      context.end_label(cmd);
    });
  } catch (...) {
    for (auto& [image, layout] : saved_layouts) image->set_layout(layout);
    throw;
  }

  barriers_ = std::move(barriers);
  pipeline_barrier_calls_ = calls;
  const std::vector<double> durations = queries.pair_durations_ms();
  for (size_t i = 0; i < passes_.size(); ++i) timings_.push_back({passes_[i].name, durations.at(i)});
}

}  // namespace vplkit
