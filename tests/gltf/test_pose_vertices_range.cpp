// The GPU posing pass (stages::add_pose_vertices_pass) binds its buffers whole, the scene's vertex
// buffer among them: a buffer past maxStorageBufferRange (the scene's vertices past 1.86M on
// lavapipe) is refused by name with the limit, before anything is recorded, not bound invalidly.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/pose_vertices.hpp"
#include "vplkit_test/context.hpp"
#include "vplkit_test/range_refusal.hpp"

#include <doctest/doctest.h>

#include <string>

TEST_CASE("pose vertices: a vertex buffer past a binding's range is refused by name") {
    vplkit::Context& ctx = vplkit::test::context();
    // Small buffers, views as large as the pass needs; the posed vertices' view one vertex past
    // the range (the buffer behind it is small: the check comes first).
    auto buffer = vplkit::Buffer::create(ctx, 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device,
                                         "pose range test");
    const vplkit::BufferView small = buffer;
    vplkit::BufferView vertices = buffer;
    vertices.name = "scene vertices";
    vertices.size = ctx.info().max_storage_buffer_range + sizeof(vplkit::scene::Vertex);
    vplkit::PassList passes("pose vertices range");
    vplkit::test::check_refused_past_range(ctx, {"scene vertices"}, [&] {
        vplkit::stages::add_pose_vertices_pass(ctx, passes, {small, small, small, small, small, vertices}, 1);
    });
}
