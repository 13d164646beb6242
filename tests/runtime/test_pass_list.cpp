// PassList: real compute passes chained through a buffer, and barriers inserted exactly where a
// hazard is (counted and checked one by one). Synchronization validation is on in the test
// context, so a barrier that is missing or too weak also fails these tests.

#include "vplkit/barriers.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/runtime_test/fill_sequence.hpp"
#include "vplkit/runtime_test/scale_add.hpp"
#include "vplkit/stages/dispatch_groups.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

using vplkit::BarrierRecord;
using vplkit::Buffer;
using vplkit::Image;
using vplkit::PassList;
using vplkit::Stage;
using vplkit::Use;

namespace fill_sequence = vplkit::runtime_test::fill_sequence;
namespace scale_add = vplkit::runtime_test::scale_add;

namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

Buffer storage(vplkit::Context& ctx, VkDeviceSize bytes, const char* name) {
    return Buffer::create(ctx, bytes, kStorage, vplkit::MemoryUse::device, name);
}

void fill(VkCommandBuffer cmd, const Buffer& b, uint32_t value) {
    vkCmdFillBuffer(cmd, b.handle(), 0, VK_WHOLE_SIZE, value);
}

void copy(VkCommandBuffer cmd, const Buffer& src, const Buffer& dst) {
    const VkBufferCopy region{0, 0, src.size()};
    vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &region);
}

void check_timings(const PassList& passes, const std::vector<std::string>& names) {
    REQUIRE(passes.timings().size() == names.size());
    for (size_t i = 0; i < names.size(); ++i) {
        CHECK(passes.timings()[i].name == names[i]);
        CHECK(passes.timings()[i].gpu_ms >= 0.0);
    }
    CHECK(passes.total_gpu_ms() >= 0.0);
}

}  // namespace

TEST_CASE("two compute passes: the second reads what the first wrote") {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t count = 777;
    auto sequence = storage(ctx, count * 4, "sequence");
    auto result = storage(ctx, count * 4, "result");
    const auto& fill_pipeline = ctx.pipeline<fill_sequence::Pipeline>(fill_sequence::Spec{64});
    const auto& scale_pipeline = ctx.pipeline<scale_add::Pipeline>();

    PassList passes("compute chain");
    passes.add("fill sequence", {Use::write(sequence)}, [&](VkCommandBuffer cmd) {
        fill_pipeline.dispatch(cmd, {sequence.descriptor()}, {count, 3, 1}, count);
    });
    passes.add("scale add", {Use::read(sequence), Use::write(result)}, [&](VkCommandBuffer cmd) {
        scale_pipeline.dispatch(cmd, {sequence.descriptor(), result.descriptor()}, {count, 2, 7}, count);
    });
    passes.run(ctx);

    const auto values = result.download<uint32_t>(count);
    for (uint32_t i = 0; i < count; ++i) REQUIRE(values[i] == (i * 3 + 1) * 2 + 7);

    // Exactly one barrier: sequence, compute write -> compute read, before the second pass.
    REQUIRE(passes.barrier_count() == 1);
    const BarrierRecord& b = passes.barriers()[0];
    CHECK(b.pass == 1);
    CHECK(b.resource == "sequence");
    CHECK(b.hazards == vplkit::hazard_read_after_write);
    CHECK(b.src_stages == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    CHECK(b.src_access == VK_ACCESS_2_SHADER_WRITE_BIT);
    CHECK(b.dst_stages == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    CHECK((b.dst_access & VK_ACCESS_2_SHADER_READ_BIT) != 0);
    CHECK(passes.pipeline_barrier_count() == 1);
    check_timings(passes, {"fill sequence", "scale add"});
    MESSAGE(passes.describe_barriers());

    // Running again gives the same barriers (tracking restarts at every run) and the same result.
    passes.run(ctx);
    CHECK(passes.barrier_count() == 1);
    CHECK(result.download<uint32_t>(count) == values);
}

TEST_CASE("compute_barrier orders dispatches inside one pass") {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t count = 300;
    auto sequence = storage(ctx, count * 4, "sequence");
    auto result = storage(ctx, count * 4, "result");
    const auto& fill_pipeline = ctx.pipeline<fill_sequence::Pipeline>(fill_sequence::Spec{32});
    const auto& scale_pipeline = ctx.pipeline<scale_add::Pipeline>();

    PassList passes;
    passes.add("fill then scale", {Use::write(sequence), Use::read(sequence), Use::write(result)},
               [&](VkCommandBuffer cmd) {
                   fill_pipeline.dispatch(cmd, {sequence.descriptor()}, {count, 1, 0}, count);
                   vplkit::compute_barrier(cmd);
                   scale_pipeline.dispatch(cmd, {sequence.descriptor(), result.descriptor()}, {count, 10, 1}, count);
               });
    passes.run(ctx);
    CHECK(passes.barrier_count() == 0);
    const auto values = result.download<uint32_t>(count);
    for (uint32_t i = 0; i < count; ++i) REQUIRE(values[i] == i * 10 + 1);
}

TEST_CASE("no barrier between independent passes or between reads") {
    vplkit::Context& ctx = vplkit::test::context();
    auto a = storage(ctx, 256, "a");
    auto b = storage(ctx, 256, "b");
    auto c = storage(ctx, 256, "c");
    auto d = storage(ctx, 256, "d");
    a.upload(std::vector<uint32_t>(64, 5u));

    PassList passes;
    passes.add("write b", {Use::transfer_dst(b)}, [&](VkCommandBuffer cmd) { fill(cmd, b, 1u); });
    passes.add("write c", {Use::transfer_dst(c)}, [&](VkCommandBuffer cmd) { fill(cmd, c, 2u); });
    // `a` was written by the host before the submission: nothing to order inside it.
    passes.add("read a into d", {Use::transfer_src(a), Use::transfer_dst(d)},
               [&](VkCommandBuffer cmd) { copy(cmd, a, d); });
    passes.run(ctx);
    CHECK(passes.barrier_count() == 0);
    CHECK(passes.pipeline_barrier_count() == 0);
    CHECK(d.download<uint32_t>(64) == std::vector<uint32_t>(64, 5u));
    check_timings(passes, {"write b", "write c", "read a into d"});
}

TEST_CASE("read after write - once per reading stage") {
    vplkit::Context& ctx = vplkit::test::context();
    auto a = storage(ctx, 256, "a");
    auto b = storage(ctx, 256, "b");
    auto c = storage(ctx, 256, "c");

    PassList passes;
    passes.add("write a", {Use::transfer_dst(a)}, [&](VkCommandBuffer cmd) { fill(cmd, a, 3u); });
    passes.add("copy a to b", {Use::transfer_src(a), Use::transfer_dst(b)},
               [&](VkCommandBuffer cmd) { copy(cmd, a, b); });
    // A second transfer read of `a`: the first barrier already made the write visible to transfers.
    passes.add("copy a to c", {Use::transfer_src(a), Use::transfer_dst(c)},
               [&](VkCommandBuffer cmd) { copy(cmd, a, c); });
    // A compute read of `a` is a new stage: it needs its own barrier.
    passes.add("compute reads a", {Use::read(a, Stage::compute)}, [](VkCommandBuffer) {});
    passes.run(ctx);

    REQUIRE(passes.barrier_count() == 2);
    CHECK(passes.barriers()[0].pass == 1);
    CHECK(passes.barriers()[0].hazards == vplkit::hazard_read_after_write);
    CHECK(passes.barriers()[1].pass == 3);
    CHECK(passes.barriers()[1].resource == "a");
    CHECK(passes.barriers()[1].src_stages == VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    CHECK(passes.barriers()[1].dst_stages == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    CHECK(c.download<uint32_t>(64) == std::vector<uint32_t>(64, 3u));
}

TEST_CASE("write after read and write after write") {
    vplkit::Context& ctx = vplkit::test::context();
    auto a = storage(ctx, 256, "a");
    auto b = storage(ctx, 256, "b");

    PassList passes;
    passes.add("write a", {Use::transfer_dst(a)}, [&](VkCommandBuffer cmd) { fill(cmd, a, 1u); });
    passes.add("copy a to b", {Use::transfer_src(a), Use::transfer_dst(b)},
               [&](VkCommandBuffer cmd) { copy(cmd, a, b); });
    passes.add("overwrite a", {Use::transfer_dst(a)}, [&](VkCommandBuffer cmd) { fill(cmd, a, 2u); });
    passes.add("overwrite b", {Use::transfer_dst(b)}, [&](VkCommandBuffer cmd) { fill(cmd, b, 4u); });
    passes.run(ctx);
    MESSAGE(passes.describe_barriers());

    REQUIRE(passes.barrier_count() == 3);
    // Before "copy a to b": a RAW.
    CHECK(passes.barriers()[0].pass == 1);
    CHECK(passes.barriers()[0].hazards == vplkit::hazard_read_after_write);
    // Before "overwrite a": a was written (pass 0) and read (pass 1) since: WAW + WAR.
    CHECK(passes.barriers()[1].pass == 2);
    CHECK(passes.barriers()[1].resource == "a");
    CHECK(passes.barriers()[1].hazards == (vplkit::hazard_write_after_write | vplkit::hazard_write_after_read));
    // Before "overwrite b": WAW on b only.
    CHECK(passes.barriers()[2].pass == 3);
    CHECK(passes.barriers()[2].resource == "b");
    CHECK(passes.barriers()[2].hazards == vplkit::hazard_write_after_write);
    CHECK(a.download<uint32_t>(64) == std::vector<uint32_t>(64, 2u));
    CHECK(b.download<uint32_t>(64) == std::vector<uint32_t>(64, 4u));
}

TEST_CASE("several barriers before one pass share one vkCmdPipelineBarrier2") {
    vplkit::Context& ctx = vplkit::test::context();
    auto a = storage(ctx, 64, "a");
    auto b = storage(ctx, 64, "b");
    auto c = storage(ctx, 128, "c");
    PassList passes;
    passes.add("write a", {Use::transfer_dst(a)}, [&](VkCommandBuffer cmd) { fill(cmd, a, 1u); });
    passes.add("write b", {Use::transfer_dst(b)}, [&](VkCommandBuffer cmd) { fill(cmd, b, 2u); });
    passes.add("gather", {Use::transfer_src(a), Use::transfer_src(b), Use::transfer_dst(c)}, [&](VkCommandBuffer cmd) {
        const VkBufferCopy first{0, 0, 64};
        const VkBufferCopy second{0, 64, 64};
        vkCmdCopyBuffer(cmd, a.handle(), c.handle(), 1, &first);
        vkCmdCopyBuffer(cmd, b.handle(), c.handle(), 1, &second);
    });
    passes.run(ctx);
    CHECK(passes.barrier_count() == 2);
    CHECK(passes.pipeline_barrier_count() == 1);
    auto values = c.download<uint32_t>(32);
    CHECK(values[0] == 1u);
    CHECK(values[31] == 2u);
}

TEST_CASE("image layouts: transitions exactly where the layout changes") {
    vplkit::Context& ctx = vplkit::test::context();
    auto image = Image::create(ctx, 9, 7, VK_FORMAT_R32_UINT, VK_IMAGE_USAGE_STORAGE_BIT, "image");
    auto out = Buffer::create(ctx, image.byte_size(), kStorage, vplkit::MemoryUse::device, "out");
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};

    PassList passes;
    passes.add("clear", {Use::transfer_dst(image)}, [&](VkCommandBuffer cmd) {
        const VkClearColorValue value{.uint32 = {11u, 0u, 0u, 0u}};
        vkCmdClearColorImage(cmd, image.handle(), image.layout(), &value, 1, &range);
    });
    passes.add("clear again", {Use::transfer_dst(image)}, [&](VkCommandBuffer cmd) {
        const VkClearColorValue value{.uint32 = {12u, 0u, 0u, 0u}};
        vkCmdClearColorImage(cmd, image.handle(), image.layout(), &value, 1, &range);
    });
    passes.add("read back", {Use::transfer_src(image), Use::transfer_dst(out)}, [&](VkCommandBuffer cmd) {
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {image.width(), image.height(), 1};
        vkCmdCopyImageToBuffer(cmd, image.handle(), image.layout(), out.handle(), 1, &region);
    });
    passes.run(ctx);
    MESSAGE(passes.describe_barriers());

    REQUIRE(passes.barrier_count() == 3);
    const auto& b = passes.barriers();
    CHECK(b[0].pass == 0);
    CHECK(b[0].is_image);
    CHECK(b[0].hazards == vplkit::hazard_layout_transition);
    CHECK(b[0].old_layout == VK_IMAGE_LAYOUT_UNDEFINED);
    CHECK(b[0].new_layout == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    CHECK(b[1].pass == 1);
    CHECK(b[1].hazards == vplkit::hazard_write_after_write);
    CHECK(b[1].old_layout == b[1].new_layout);
    CHECK(b[2].pass == 2);
    CHECK(b[2].hazards == (vplkit::hazard_read_after_write | vplkit::hazard_layout_transition));
    CHECK(b[2].old_layout == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    CHECK(b[2].new_layout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    CHECK(image.layout() == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    CHECK(out.download<uint32_t>(63) == std::vector<uint32_t>(63, 12u));

    // The layout persists: the next run starts from TRANSFER_SRC_OPTIMAL.
    passes.run(ctx);
    REQUIRE(passes.barrier_count() == 3);
    CHECK(passes.barriers()[0].old_layout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

TEST_CASE("an image read in compute after a transfer write goes to GENERAL") {
    vplkit::Context& ctx = vplkit::test::context();
    auto image = Image::create(ctx, 4, 4, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "storage image");
    image.upload(std::vector<float>(16, 1.0f));
    PassList passes;
    passes.add("shader reads", {Use::read(image, Stage::compute)}, [](VkCommandBuffer) {});
    passes.add("shader reads again", {Use::read(image, Stage::compute)}, [](VkCommandBuffer) {});
    passes.run(ctx);
    REQUIRE(passes.barrier_count() == 1);
    CHECK(passes.barriers()[0].old_layout == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    CHECK(passes.barriers()[0].new_layout == VK_IMAGE_LAYOUT_GENERAL);
    CHECK(image.layout() == VK_IMAGE_LAYOUT_GENERAL);
}

TEST_CASE("host reads get a barrier to the host stage") {
    vplkit::Context& ctx = vplkit::test::context();
    auto readback = Buffer::create(ctx, 64, kStorage, vplkit::MemoryUse::readback, "readback");
    PassList passes;
    passes.add("write", {Use::transfer_dst(readback)}, [&](VkCommandBuffer cmd) { fill(cmd, readback, 6u); });
    passes.add("host reads", {Use::host_read(readback)}, [](VkCommandBuffer) {});
    passes.run(ctx);
    REQUIRE(passes.barrier_count() == 1);
    CHECK(passes.barriers()[0].dst_stages == VK_PIPELINE_STAGE_2_HOST_BIT);
    CHECK(passes.barriers()[0].dst_access == VK_ACCESS_2_HOST_READ_BIT);
    CHECK(readback.download<uint32_t>(16) == std::vector<uint32_t>(16, 6u));
}

TEST_CASE("uses that cannot happen are rejected when the pass is added") {
    vplkit::Context& ctx = vplkit::test::context();
    auto buffer = storage(ctx, 64, "buffer");
    auto image = Image::create(ctx, 2, 2, VK_FORMAT_R32_UINT, VK_IMAGE_USAGE_STORAGE_BIT, "image");
    PassList passes;
    auto nothing = [](VkCommandBuffer) {};
    CHECK_THROWS_WITH_AS(
        passes.add("two layouts", {Use::transfer_src(image), Use::read(image, Stage::compute)}, nothing),
        doctest::Contains("in two layouts"), vplkit::Error);
    CHECK_THROWS_WITH_AS(passes.add("indirect write", {Use::write(buffer, Stage::indirect)}, nothing),
                         doctest::Contains("which only reads"), vplkit::Error);
    CHECK_THROWS_WITH_AS(passes.add("buffer attachment", {Use::write(buffer, Stage::color_attachment)}, nothing),
                         doctest::Contains("takes images only"), vplkit::Error);
    CHECK_THROWS_WITH_AS(passes.add("no record", {Use::read(buffer)}, nullptr),
                         doctest::Contains("no recording function"), vplkit::Error);
    CHECK(passes.size() == 0);
    // The same resource twice in one pass is merged into one access.
    passes.add("merged", {Use::read(buffer, Stage::compute), Use::read(buffer, Stage::transfer)}, nothing);
    passes.run(ctx);
    CHECK(passes.barrier_count() == 0);
}

TEST_CASE("a grid past 65,535 workgroups that cannot be folded is refused, naming the pass or the step") {
    // fill_sequence.comp reads gl_GlobalInvocationID: its grid is not folded (docs/codegen.md).
    vplkit::Context& ctx = vplkit::test::context();
    fill_sequence::Spec spec;
    spec.local_size_x = 1;
    const auto& pipeline = ctx.pipeline<fill_sequence::Pipeline>(spec);
    CHECK_FALSE(fill_sequence::kFoldsGrid);
    vplkit::stages::check_dispatch_groups(pipeline, "fill", 65535);
    CHECK_THROWS_WITH_AS(vplkit::stages::check_dispatch_groups(pipeline, "fill", 65536),
                         doctest::Contains("fill: shader 'fill_sequence': 65536 x 1 x 1 threads need 65536 x 1 x 1 "
                                           "workgroups, more than 65535"),
                         vplkit::Error);
    // Thrown while recording (a step that skipped the check): the step list names the step.
    vplkit::StepList steps;
    steps.add("too wide", {}, [](VkCommandBuffer) { throw std::length_error("shader 'x': too wide"); });
    CHECK_THROWS_WITH_AS(steps.record(VK_NULL_HANDLE), "step 'too wide': shader 'x': too wide", vplkit::Error);
}

TEST_CASE("an empty pass list runs") {
    PassList passes;
    passes.run(vplkit::test::context());
    CHECK(passes.timings().empty());
}
