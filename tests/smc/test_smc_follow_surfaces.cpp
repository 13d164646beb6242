// SMC in a posed scene: smc_triangle_slots.comp (each scene triangle's slot in the BVH's leaf
// order) and smc_follow_surfaces.comp (each VPL put at its barycentric point of its triangle's
// new pose, its normal the triangle's new one on the same side), against double precision.
// Eight triangles (four squares of two); the first square turns 40 degrees about an axis through
// it and moves; the BVH is built anew from the moved triangles, so its leaves are in another
// order than the first build's (as after the first move's GPU build): a VPL looked up by its
// leaf rather than its scene triangle lands on the wrong one. Checked: every live VPL at the
// moved point (1e-5) with the moved normal (1e-5), flipped where kSmcFlipped says; a dead VPL
// and the slots past |Y| left as they were; a VPL whose triangle the BVH lacks made dead (both
// radiosities zero).

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/smc_follow_surfaces.hpp"
#include "vplkit/shaders/smc_triangle_slots.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <vector>

namespace {

using vplkit::shaders::SmcCounters;
using vplkit::shaders::SmcVpl;

constexpr uint32_t kFlipped = 8u, kDead = 4u;

vplkit::Buffer make(size_t bytes, const char* name) {
    return vplkit::Buffer::create(vplkit::test::context(), std::max<size_t>(bytes, 16),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
}

// Four unit squares side by side along x at z = 0, two triangles each, facing +z.
std::vector<glm::vec3> squares() {
    std::vector<glm::vec3> t;
    for (int s = 0; s < 4; ++s) {
        const float x = 1.5f * float(s);
        const glm::vec3 a{x, 0, 0}, b{x + 1, 0, 0}, c{x + 1, 1, 0}, d{x, 1, 0};
        for (const glm::vec3& v : {a, b, c, a, c, d}) t.push_back(v);
    }
    return t;
}

std::vector<SmcVpl> follow(const std::vector<glm::vec3>& triangles, std::vector<SmcVpl> state, uint32_t count) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t budget = uint32_t(state.size());
    const uint32_t slot_count = uint32_t(triangles.size() / 3);
    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(triangles));
    auto state_buffer = make(budget * sizeof(SmcVpl), "state");
    auto slots = make(slot_count * 4, "slots");
    auto counter_buffer = make(sizeof(SmcCounters), "counters");
    state_buffer.upload(state);
    slots.upload(std::vector<uint32_t>(slot_count, 0xffffffffu));
    SmcCounters counters{};
    counters.vpl_count = count;
    counter_buffer.upload(std::vector<SmcCounters>{counters});

    namespace slot_shader = vplkit::shaders::smc_triangle_slots;
    const auto& slot_pipeline = ctx.pipeline<slot_shader::Pipeline>(vplkit::stages::bvh_spec<slot_shader::Spec>(bvh));
    slot_shader::Bindings sb;
    vplkit::stages::bind_bvh(sb, bvh);
    sb.slots = slots.descriptor();
    slot_shader::Push slot_push{};
    slot_push.triangle_count = bvh.triangle_count;
    slot_push.slot_count = slot_count;
    namespace shader = vplkit::shaders::smc_follow_surfaces;
    const auto& pipeline = ctx.pipeline<shader::Pipeline>(vplkit::stages::bvh_spec<shader::Spec>(bvh));
    shader::Bindings b;
    vplkit::stages::bind_bvh(b, bvh);
    b.state = state_buffer.descriptor();
    b.slots = slots.descriptor();
    b.counters = counter_buffer.descriptor();
    shader::Push push{};
    push.budget = budget;
    push.triangle_count = bvh.triangle_count;
    push.slot_count = slot_count;
    vplkit::PassList passes("smc follow test");
    passes.add("smc triangle slots", vplkit::stages::binding_uses<slot_shader::Module>(sb, {}),
               [&](VkCommandBuffer cmd) { slot_pipeline.dispatch(cmd, sb, slot_push, bvh.triangle_count); });
    passes.add("smc follow surfaces", vplkit::stages::binding_uses<shader::Module>(b, {}),
               [&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, b, push, budget); });
    passes.run(ctx);
    return state_buffer.download<SmcVpl>(budget);
}

glm::dvec3 d3(const vplkit::shaders::vec3& v) {
    return {v.x, v.y, v.z};
}

}  // namespace

TEST_CASE("smc follow surfaces: VPLs move with their triangles, by scene index, on the same side") {
    const std::vector<glm::vec3> before = squares();
    // The first square turned 40 degrees about the axis (0.3, 1, 0.2) through (0.5, 0.5, 0), moved by (0.2, -0.1, 0.7).
    const glm::mat4 pose = glm::translate(glm::mat4(1.0f), glm::vec3(0.7f, 0.4f, 0.7f)) *
                           glm::rotate(glm::mat4(1.0f), glm::radians(40.0f), glm::normalize(glm::vec3(0.3f, 1, 0.2f))) *
                           glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, -0.5f, 0.0f));
    std::vector<glm::vec3> after = before;
    for (size_t v = 0; v < 6; ++v) after[v] = glm::vec3(pose * glm::vec4(before[v], 1.0f));

    // Per triangle (8) a VPL at barycentrics (0.2 + 0.05 t, 0.3), the odd ones on the back.
    std::vector<SmcVpl> state;
    for (uint32_t t = 0; t < 8; ++t) {
        SmcVpl v{};
        v.triangle = t;
        v.barycentrics = {0.2f + 0.05f * float(t), 0.3f};
        v.flags = 3u | (t % 2 == 1 ? kFlipped : 0u);
        v.radiosity = v.choice_radiosity = {1.0f, 2.0f, 3.0f};
        state.push_back(v);
    }
    SmcVpl dead = state[0];
    dead.flags |= kDead;
    dead.position = {9.0f, 9.0f, 9.0f};
    state.push_back(dead);
    SmcVpl lost = state[2];
    lost.triangle = 8;  // no such triangle
    state.push_back(lost);
    const uint32_t count = uint32_t(state.size());
    SmcVpl past = state[1];  // past |Y|: untouched
    past.position = {5.0f, 5.0f, 5.0f};
    state.push_back(past);

    const std::vector<SmcVpl> out = follow(after, state, count);
    for (uint32_t t = 0; t < 8; ++t) {
        CAPTURE(t);
        const glm::dvec3 a(after[3 * t]), b(after[3 * t + 1]), c(after[3 * t + 2]);
        const double b1 = state[t].barycentrics.x, b2 = state[t].barycentrics.y;
        const glm::dvec3 expected = (1.0 - b1 - b2) * a + b1 * b + b2 * c;
        glm::dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
        if (t % 2 == 1) normal = -normal;
        CHECK(glm::length(d3(out[t].position) - expected) < 1e-5);
        CHECK(glm::length(d3(out[t].normal) - normal) < 1e-5);
        CHECK(out[t].flags == state[t].flags);
        CHECK(out[t].radiosity.z == 3.0f);
    }
    CHECK(glm::length(d3(out[0].normal) - glm::dvec3(0, 0, 1)) > 0.5);  // the turned square's normal did turn
    CHECK(out[8].position.x == 9.0f);                                   // dead: left as it was
    CHECK(out[9].flags == (state[9].flags | kDead));                    // its triangle is gone: dead
    CHECK(out[9].radiosity.x == 0.0f);
    CHECK(out[9].choice_radiosity.y == 0.0f);
    CHECK(out[10].position.x == 5.0f);  // past |Y|
}
