#pragma once
// PassList: a small frame graph. Passes are recorded in the order they were added; each pass
// declares which buffers and images it touches and how, and run() inserts a synchronization2
// barrier before a pass only where a declared use conflicts with an earlier one
// (read-after-write, write-after-write, write-after-read, or an image layout change).
//
//   vplkit::PassList passes;
//   passes.add("keys", {Use::read(vpls), Use::write(keys)}, [&](VkCommandBuffer cmd) { ... });
//   passes.add("sort", {Use::read_write(keys)}, [&](VkCommandBuffer cmd) { ... });
//   passes.run(ctx);            // one command buffer, submitted and waited for
//   for (auto& t : passes.timings()) std::printf("%s %.3f ms\n", t.name.c_str(), t.gpu_ms);
//
// Resources are tracked whole (no sub-ranges). Buffer and Image objects named in uses must stay
// alive, at the same address, while run() executes. Tracking starts fresh at every run():
// the runtime ends every submission with a full memory barrier, so nothing from an earlier
// submission needs synchronizing. Image layouts persist in the Image objects across runs.

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vplkit {

class Buffer;
class Context;
class Image;

// Where a pass touches a resource. Combine with | when one pass uses it in several stages.
enum class Stage : uint32_t {
  compute = 1u << 0,
  vertex = 1u << 1,
  fragment = 1u << 2,
  transfer = 1u << 3,          // copies, fills, clears, blits
  host = 1u << 4,              // the CPU reads it after the submission
  indirect = 1u << 5,          // indirect dispatch/draw arguments
  vertex_input = 1u << 6,      // vertex and index buffers
  color_attachment = 1u << 7,
  depth_attachment = 1u << 8,  // depth/stencil tests and writes
};
constexpr Stage operator|(Stage a, Stage b) { return Stage(uint32_t(a) | uint32_t(b)); }
constexpr bool has_stage(Stage set, Stage s) { return (uint32_t(set) & uint32_t(s)) != 0; }

enum class Access { read, write, read_write };

struct Use {
  const Buffer* buffer = nullptr;
  Image* image = nullptr;
  Access access = Access::read;
  Stage stages = Stage::compute;
  // For images: the layout the pass needs. VK_IMAGE_LAYOUT_UNDEFINED = the default for the
  // stage and access: GENERAL for shader access (valid for both storage and sampled images),
  // TRANSFER_SRC/DST_OPTIMAL for transfer reads/writes, the attachment layouts for attachments.
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;

  static Use read(const Buffer& buffer, Stage stages = Stage::compute);
  static Use write(const Buffer& buffer, Stage stages = Stage::compute);
  static Use read_write(const Buffer& buffer, Stage stages = Stage::compute);
  static Use transfer_src(const Buffer& buffer) { return read(buffer, Stage::transfer); }
  static Use transfer_dst(const Buffer& buffer) { return write(buffer, Stage::transfer); }
  static Use indirect(const Buffer& buffer) { return read(buffer, Stage::indirect); }
  // The host reads the buffer once run() returns (a mapped readback buffer).
  static Use host_read(const Buffer& buffer) { return read(buffer, Stage::host); }

  static Use read(Image& image, Stage stages = Stage::compute, VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED);
  static Use write(Image& image, Stage stages = Stage::compute, VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED);
  static Use read_write(Image& image, Stage stages = Stage::compute,
                        VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED);
  // Sampled through a combined image sampler / sampled image in SHADER_READ_ONLY_OPTIMAL.
  static Use sampled(Image& image, Stage stages = Stage::fragment) {
    return read(image, stages, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  }
  static Use transfer_src(Image& image) { return read(image, Stage::transfer); }
  static Use transfer_dst(Image& image) { return write(image, Stage::transfer); }
  static Use color_attachment(Image& image) { return read_write(image, Stage::color_attachment); }
  static Use depth_attachment(Image& image) { return read_write(image, Stage::depth_attachment); }
};

struct PassTiming {
  std::string name;
  double gpu_ms = 0.0;  // GPU time from the end of everything before the pass to its own end
};

// Why a barrier was inserted (bit set).
enum Hazard : uint32_t {
  hazard_read_after_write = 1u << 0,
  hazard_write_after_write = 1u << 1,
  hazard_write_after_read = 1u << 2,
  hazard_layout_transition = 1u << 3,
};

// One buffer or image barrier that run() recorded.
struct BarrierRecord {
  size_t pass = 0;        // index of the pass it was recorded before
  std::string resource;   // the buffer's or image's name ("" when unnamed)
  bool is_image = false;
  uint32_t hazards = 0;   // Hazard bits
  VkPipelineStageFlags2 src_stages = 0;
  VkAccessFlags2 src_access = 0;
  VkPipelineStageFlags2 dst_stages = 0;
  VkAccessFlags2 dst_access = 0;
  VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImageLayout new_layout = VK_IMAGE_LAYOUT_UNDEFINED;

  // "before 'sort': keys RAW (compute write -> compute read)"
  std::string describe(const std::vector<std::string>& pass_names) const;
};

class PassList {
 public:
  using Record = std::function<void(VkCommandBuffer)>;

  // `name` labels the whole command buffer in debuggers.
  explicit PassList(std::string name = "vplkit passes") : name_(std::move(name)) {}

  // Appends a pass. `uses` lists every buffer and image the pass reads or writes; a resource
  // may appear several times (the uses are merged), but an image must not be asked for in two
  // different layouts in one pass (Error).
  PassList& add(std::string name, std::vector<Use> uses, Record record);

  // Records every pass into one command buffer with the barriers the uses call for, a debug
  // label and a pair of timestamps around each pass, submits it and waits. Can be called again.
  void run(Context& context);

  size_t size() const { return passes_.size(); }
  void clear();

  // Of the last run(): one entry per pass, in order.
  const std::vector<PassTiming>& timings() const { return timings_; }
  double total_gpu_ms() const;
  // Of the last run(): every barrier, in recording order (buffer and image barriers counted
  // one by one; several of them before one pass share one vkCmdPipelineBarrier2 call).
  const std::vector<BarrierRecord>& barriers() const { return barriers_; }
  size_t barrier_count() const { return barriers_.size(); }
  // Number of vkCmdPipelineBarrier2 calls of the last run (not counting the final host barrier).
  size_t pipeline_barrier_count() const { return pipeline_barrier_calls_; }
  // Barriers of the last run, one describe() line each.
  std::string describe_barriers() const;

 private:
  struct Pass {
    std::string name;
    std::vector<Use> uses;
    Record record;
  };

  std::string name_;
  std::vector<Pass> passes_;
  std::vector<PassTiming> timings_;
  std::vector<BarrierRecord> barriers_;
  size_t pipeline_barrier_calls_ = 0;
};

}  // namespace vplkit
