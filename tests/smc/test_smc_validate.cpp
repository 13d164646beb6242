// The indirect-visibility test of the SMC paper sec. 3.2.2 with its mailboxes, shader by shader,
// against smc_reference.cpp (double precision, every triangle tested).
// - smc_validate.comp: a VPL stays valid while the camera sees its anchor (in the frustum, on the
//   anchor's front side, no triangle between). On a floor with an occluding plate seen from
//   above: anchors under the plate, outside the frustum, facing away or behind the camera are
//   invalid (and one nearer than the near plane), the others valid; valid[] must equal the reference exactly and
//   smc_invalid_list.comp's list hold exactly the invalid VPLs in index order. Fails on a wrong frustum, facing or
//   shadow test, a lost, doubled or misordered list entry, or a slot past |Y| touched. Hard cases: every VPL invalid
//   (over several chunks of the compaction), |Y| = 0.
//   After the geometry moved (surfaces_moved): a VPL no longer on its own triangle (lifted off the
//   floor, or the floor under it another triangle now) is dead (flag set, both radiosities zero)
//   and invalid, a VPL its anchor no longer sees (the plate between them) invalid but not dead,
//   one on its surface and seen valid; without the flag the mailbox alone decides (all valid).
// - smc_revalidate.comp: each camera point draws `tries` entries of the invalid list from its own
//   stream (replayed here) and claims a drawn VPL it sees, each facing the other. The VPLs it
//   validates (smc_revalidate_claims.comp after each round) must be exactly those some point drew and saw (the
//   reference's seers), their new anchor the seer of lowest pool index (whatever the scheduling), the revalidated
//   count their number,
//   and nothing else changes. VPLs above a plate that hides them from every camera point stay
//   invalid. Fails if a hidden VPL is claimed, a seen one missed, a valid one re-anchored, or a
//   claim counted twice. Both rounds' streams, the two in turn (the second claims only what
//   the first left), an empty invalid list, coincident camera points.
// Every point here is at least 0.05 from any silhouette the tests cross, far above float error.

#include "smc_reference.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/smc_invalid_list.hpp"
#include "vplkit/shaders/smc_revalidate.hpp"
#include "vplkit/shaders/smc_revalidate_claims.hpp"
#include "vplkit/shaders/smc_validate.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <random>
#include <vector>

namespace {

using vplkit::reference::SmcPoint;
using vplkit::reference::Triangle;
using vplkit::shaders::SmcCounters;
using vplkit::shaders::SmcVpl;

vplkit::Buffer make(size_t bytes, const char* name) {
    return vplkit::Buffer::create(vplkit::test::context(), std::max<size_t>(bytes, 16),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
}

// A square [lo, hi]^2 at height z as two triangles facing +z.
void add_square(std::vector<glm::vec3>& t, float lo, float hi, float z) {
    const glm::vec3 a{lo, lo, z}, b{hi, lo, z}, c{hi, hi, z}, d{lo, hi, z};
    for (const glm::vec3& v : {a, b, c, a, c, d}) t.push_back(v);
}

std::vector<Triangle> reference_triangles(const std::vector<glm::vec3>& t) {
    std::vector<Triangle> out;
    for (size_t i = 0; i + 2 < t.size(); i += 3) {
        out.push_back(
            {{t[i].x, t[i].y, t[i].z}, {t[i + 1].x, t[i + 1].y, t[i + 1].z}, {t[i + 2].x, t[i + 2].y, t[i + 2].z}});
    }
    return out;
}

vplkit::shaders::vec3 v3(glm::dvec3 v) {
    return {float(v.x), float(v.y), float(v.z)};
}
glm::dvec3 d3(const vplkit::shaders::vec3& v) {
    return {v.x, v.y, v.z};
}

// ---- smc_validate.comp ----

// Floor [-4, 4]^2 at z = 0, a plate [-0.5, 0.5]^2 at z = 2; the camera at (0, 0, 5) looks down
// with a 60 degree field of view (the floor is in view for |x|, |y| < 2.88).
struct ValidateScene {
    std::vector<glm::vec3> triangles;
    glm::vec3 camera{0.0f, 0.0f, 5.0f};
    glm::mat4 view_projection;
    ValidateScene() {
        add_square(triangles, -4.0f, 4.0f, 0.0f);
        add_square(triangles, -0.5f, 0.5f, 2.0f);
        view_projection = vplkit::stages::vulkan_perspective(glm::radians(60.0f), 1.0f, 0.1f, 20.0f) *
                          glm::lookAt(camera, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    }
};

struct Validated {
    std::vector<SmcVpl> state;
    std::vector<uint32_t> valid;
    std::vector<uint32_t> invalid_list;
    SmcCounters counters{};
};

Validated run_validate(const ValidateScene& s, const std::vector<SmcVpl>& state, uint32_t vpl_count,
                       bool surfaces_moved = false) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t budget = uint32_t(state.size());
    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(s.triangles));
    auto state_buffer = make(budget * sizeof(SmcVpl), "state");
    auto valid = make(budget * 4, "valid");
    auto invalid_list = make(budget * 4, "invalid list");
    auto counter_buffer = make(sizeof(SmcCounters), "counters");
    state_buffer.upload(state);
    valid.upload(std::vector<uint32_t>(budget, 7u));  // 7: not written
    invalid_list.upload(std::vector<uint32_t>(budget, 0xdeadu));
    SmcCounters counters{};
    counters.vpl_count = vpl_count;
    counter_buffer.upload(std::vector<SmcCounters>{counters});

    namespace shader = vplkit::shaders::smc_validate;
    const auto& pipeline = ctx.pipeline<shader::Pipeline>(vplkit::stages::bvh_spec<shader::Spec>(bvh));
    shader::Bindings b;
    vplkit::stages::bind_bvh(b, bvh);
    b.state = state_buffer.descriptor();
    b.valid = valid.descriptor();
    b.counters = counter_buffer.descriptor();
    shader::Push push{};
    std::memcpy(&push.view_projection, &s.view_projection, sizeof(push.view_projection));
    push.camera_position = {s.camera.x, s.camera.y, s.camera.z};
    push.budget = budget;
    push.surfaces_moved = surfaces_moved ? 1u : 0u;
    namespace list_shader = vplkit::shaders::smc_invalid_list;
    const auto& list_pipeline = ctx.pipeline<list_shader::Pipeline>();
    list_shader::Bindings lb;
    lb.valid = valid.descriptor();
    lb.invalid_list = invalid_list.descriptor();
    lb.counters = counter_buffer.descriptor();
    list_shader::Push list_push{};
    list_push.budget = budget;
    vplkit::PassList passes("smc validate test");
    passes.add("smc validate", vplkit::stages::binding_uses<shader::Module>(b, {}),
               [&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, b, push, budget); });
    passes.add("smc invalid list", vplkit::stages::binding_uses<list_shader::Module>(lb, {}), [&](VkCommandBuffer cmd) {
        list_pipeline.dispatch(cmd, lb, list_push, list_pipeline.workgroup_size[0]);
    });
    passes.run(ctx);
    Validated v;
    v.state = state_buffer.download<SmcVpl>(budget);
    v.valid = valid.download<uint32_t>(budget);
    v.counters = counter_buffer.download<SmcCounters>(1)[0];
    v.invalid_list = invalid_list.download<uint32_t>(budget);
    v.invalid_list.resize(std::min(v.counters.invalid_count, budget));
    return v;
}

SmcVpl with_anchor(glm::dvec3 anchor, glm::dvec3 normal) {
    SmcVpl v{};
    v.position = {9.0f, 9.0f, 9.0f};  // the VPL itself plays no part in the mailbox test
    v.anchor = v3(anchor);
    v.anchor_normal = v3(glm::normalize(normal));
    return v;
}

// Runs validate and compares with the reference; returns the expected invalid count.
uint32_t check_validate(const std::vector<SmcVpl>& state, uint32_t vpl_count) {
    const ValidateScene s;
    const auto triangles = reference_triangles(s.triangles);
    const Validated got = run_validate(s, state, vpl_count);
    std::vector<uint32_t> expected_invalid;  // in index order
    for (uint32_t i = 0; i < state.size(); ++i) {
        CAPTURE(i);
        if (i >= vpl_count) {
            CHECK(got.valid[i] == 7u);
            continue;
        }
        const bool seen =
            vplkit::reference::smc_anchor_seen(glm::dmat4(s.view_projection), glm::dvec3(s.camera), d3(state[i].anchor),
                                               d3(state[i].anchor_normal), triangles);
        CHECK(got.valid[i] == (seen ? 1u : 0u));
        if (!seen) expected_invalid.push_back(i);
    }
    CHECK(got.counters.invalid_count == expected_invalid.size());
    CHECK(got.invalid_list == expected_invalid);
    return uint32_t(expected_invalid.size());
}

// ---- smc_revalidate.comp ----

// Camera points on the floor [-1, 1]^2 (z = 0, facing up); a plate [-2, 2]^2 at z = 1.5. VPLs at
// z = 3 facing down are above the plate, hidden from every camera point; VPLs at z = 1 facing
// down are below it, seen by every camera point; VPLs at z = 1 facing up are seen by none.
struct RevalidateScene {
    std::vector<glm::vec3> triangles;
    std::vector<SmcPoint> points;
    std::vector<SmcPoint> vpls;
    RevalidateScene() {
        add_square(triangles, -3.0f, 3.0f, 0.0f);
        add_square(triangles, -2.0f, 2.0f, 1.5f);
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> unit(-1.0, 1.0);
        for (int j = 0; j < 24; ++j) {
            SmcPoint p;
            p.position = {unit(rng), unit(rng), 0.0};
            p.covered = j % 6 != 5;  // some pool entries are not camera points
            points.push_back(p);
        }
        points[7].position = points[3].position;  // coincident camera points
        for (int i = 0; i < 18; ++i) {
            SmcPoint v;
            const int kind = i % 3;  // 0: hidden above, 1: seen below, 2: facing away
            v.position = {0.8 * unit(rng), 0.8 * unit(rng), kind == 0 ? 3.0 : 1.0};
            v.normal = {0.0, 0.0, kind == 2 ? 1.0 : -1.0};
            vpls.push_back(v);
        }
    }
};

struct Revalidated {
    std::vector<SmcVpl> state;
    std::vector<uint32_t> valid;
    uint32_t revalidated = 0;
};

Revalidated run_revalidate(const RevalidateScene& s, const std::vector<uint32_t>& valid,
                           const std::vector<uint32_t>& invalid_list, uint32_t tries, uint32_t seed, uint32_t iteration,
                           const std::vector<uint32_t>& rounds) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t budget = uint32_t(s.vpls.size()), pool = uint32_t(s.points.size());
    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(s.triangles));
    std::vector<SmcVpl> hits(pool), state(budget);
    for (uint32_t j = 0; j < pool; ++j) {
        hits[j] = SmcVpl{};
        hits[j].anchor = v3(s.points[j].position);
        hits[j].anchor_normal = v3(s.points[j].normal);
        hits[j].flags = s.points[j].covered ? 1u : 0u;
    }
    for (uint32_t i = 0; i < budget; ++i) {
        state[i] = SmcVpl{};
        state[i].position = v3(s.vpls[i].position);
        state[i].normal = v3(s.vpls[i].normal);
        state[i].anchor = {-5.0f, -5.0f, float(i)};  // the old mailbox
        state[i].anchor_normal = {0.0f, 0.0f, 1.0f};
    }
    std::vector<uint32_t> list = invalid_list;
    list.resize(budget, 0u);
    auto hit_buffer = make(pool * sizeof(SmcVpl), "hits");
    auto state_buffer = make(budget * sizeof(SmcVpl), "state");
    auto valid_buffer = make(budget * 4, "valid");
    auto list_buffer = make(budget * 4, "invalid list");
    auto counter_buffer = make(sizeof(SmcCounters), "counters");
    hit_buffer.upload(hits);
    state_buffer.upload(state);
    valid_buffer.upload(valid);
    list_buffer.upload(list);
    SmcCounters counters{};
    counters.vpl_count = budget;
    counters.invalid_count = uint32_t(invalid_list.size());
    counter_buffer.upload(std::vector<SmcCounters>{counters});

    namespace shader = vplkit::shaders::smc_revalidate;
    const auto& pipeline = ctx.pipeline<shader::Pipeline>(vplkit::stages::bvh_spec<shader::Spec>(bvh));
    shader::Bindings b;
    vplkit::stages::bind_bvh(b, bvh);
    b.hits = hit_buffer.descriptor();
    b.state = state_buffer.descriptor();
    b.valid = valid_buffer.descriptor();
    b.invalid_list = list_buffer.descriptor();
    b.counters = counter_buffer.descriptor();
    shader::Push push{};
    push.point_count = pool;
    push.tries = tries;
    push.seed = seed;
    push.iteration = iteration;
    namespace claims_shader = vplkit::shaders::smc_revalidate_claims;
    const auto& claims_pipeline = ctx.pipeline<claims_shader::Pipeline>();
    claims_shader::Bindings cb;
    cb.hits = hit_buffer.descriptor();
    cb.state = state_buffer.descriptor();
    cb.valid = valid_buffer.descriptor();
    cb.counters = counter_buffer.descriptor();
    claims_shader::Push claims_push{};
    claims_push.budget = budget;
    vplkit::PassList passes("smc revalidate test");
    for (const uint32_t round : rounds) {
        push.round = round;
        passes.add("smc revalidate", vplkit::stages::binding_uses<shader::Module>(b, {}),
                   [&pipeline, b, push, pool](VkCommandBuffer cmd) { pipeline.dispatch(cmd, b, push, pool); });
        passes.add("smc revalidate claims", vplkit::stages::binding_uses<claims_shader::Module>(cb, {}),
                   [&claims_pipeline, cb, claims_push, budget](VkCommandBuffer cmd) {
                       claims_pipeline.dispatch(cmd, cb, claims_push, budget);
                   });
    }
    passes.run(ctx);
    return {state_buffer.download<SmcVpl>(budget), valid_buffer.download<uint32_t>(budget),
            counter_buffer.download<SmcCounters>(1)[0].revalidated};
}

// Runs the rounds one after the other and compares with the reference; returns how many VPLs
// they validated. A VPL is claimed in the first round in which some point draws and sees it
// (the draws do not depend on what is valid: a later round only skips it), by the lowest-index one of that
// round's seers, and counted once.
uint32_t check_revalidate(const RevalidateScene& s, const std::vector<uint32_t>& invalid_list, uint32_t tries,
                          uint32_t seed, uint32_t iteration, const std::vector<uint32_t>& rounds) {
    std::vector<uint32_t> valid(s.vpls.size(), 1u);
    for (uint32_t i : invalid_list) valid[i] = 0u;
    const Revalidated got = run_revalidate(s, valid, invalid_list, tries, seed, iteration, rounds);
    std::vector<std::vector<uint32_t>> seers(s.vpls.size());
    for (const uint32_t round : rounds) {
        const auto round_seers = vplkit::reference::smc_revalidation_seers(
            s.points, s.vpls, invalid_list, tries, seed, iteration, round, reference_triangles(s.triangles));
        for (size_t i = 0; i < seers.size(); ++i) {
            if (seers[i].empty()) seers[i] = round_seers[i];
        }
    }
    uint32_t expected = 0;
    for (uint32_t i = 0; i < s.vpls.size(); ++i) {
        CAPTURE(i);
        if (seers[i].empty()) {
            CHECK(got.valid[i] == valid[i]);  // unchanged
            CHECK(got.state[i].anchor.x == -5.0f);
            continue;
        }
        ++expected;
        CHECK(got.valid[i] == 1u);
        // The new mailbox: the camera point of lowest pool index that drew and saw it.
        const uint32_t winner = *std::min_element(seers[i].begin(), seers[i].end());
        const bool from_winner = d3(got.state[i].anchor) == d3(v3(s.points[winner].position));
        CHECK(from_winner);
        CHECK(got.state[i].anchor_normal.z == 1.0f);
        CHECK(i % 3 == 1);  // only the VPLs below the plate, facing the floor, can be seen
    }
    CHECK(got.revalidated == expected);
    return expected;
}

}  // namespace

TEST_CASE("smc validate: an anchor the camera sees keeps its VPL valid, the others are listed invalid") {
    const glm::dvec3 up{0.0, 0.0, 1.0};
    std::vector<SmcVpl> state = {
        with_anchor({2.0, 2.0, 0.0}, up),                 // seen
        with_anchor({0.1, 0.1, 0.0}, up),                 // under the plate
        with_anchor({-1.5, 0.7, 0.0}, up),                // seen
        with_anchor({3.5, 0.0, 0.0}, up),                 // outside the frustum
        with_anchor({1.0, -1.0, 0.0}, -up),               // facing away from the camera
        with_anchor({0.0, 0.0, 6.0}, up),                 // behind the camera
        with_anchor({-0.3, 0.2, 0.0}, up),                // under the plate
        with_anchor({0.1, -0.2, 2.0}, up),                // on the plate itself, facing the camera: seen
        with_anchor({2.5, -2.5, 0.0}, up),                // seen, near the corner of the view
        with_anchor({-1.0, -1.0, 1.0}, {1.0, 0.0, 0.3}),  // seen at an angle (a wall's point)
        with_anchor({0.01, 0.01, 4.95}, up),              // before the near plane (0.1): clip z < 0
    };
    const uint32_t count = uint32_t(state.size());
    state.push_back(with_anchor({0.5, 0.5, 0.0}, up));  // past |Y|
    state.push_back(with_anchor({0.6, 0.5, 0.0}, up));
    const uint32_t invalid = check_validate(state, count);
    CHECK(invalid == 6);
}

TEST_CASE("smc validate: after the geometry moved, VPLs off their triangle are dead and occluded ones invalid") {
    const ValidateScene s;  // floor triangles 0 (x > y) and 1, the plate (2, 3) at z = 2
    auto vpl = [](glm::vec3 p, uint32_t triangle, glm::dvec3 anchor) {
        SmcVpl v = with_anchor(anchor, {0.0, 0.0, 1.0});
        v.position = {p.x, p.y, p.z};
        v.normal = {0.0f, 0.0f, 1.0f};
        v.triangle = triangle;
        v.radiosity = v.choice_radiosity = {1.0f, 2.0f, 3.0f};
        return v;
    };
    const std::vector<SmcVpl> state = {
        vpl({1.0f, -1.0f, 0.0f}, 0, {2.0, 1.0, 0.0}),  // on its triangle, seen: valid
        vpl({1.0f, -1.0f, 0.5f}, 0, {2.0, 1.0, 0.0}),  // its surface left it (now 0.5 below): dead
        vpl({1.5f, -0.5f, 0.0f}, 1, {2.0, 1.0, 0.0}),  // triangle 1 is not under it any more: dead
        vpl({0.3f, -0.2f, 0.0f}, 0, {0.0, 0.0, 2.0}),  // its anchor on the plate, the plate between
    };
    const Validated still = run_validate(s, state, 4, false);
    CHECK(still.valid == std::vector<uint32_t>{1u, 1u, 1u, 1u});  // every anchor seen: the mailbox alone
    for (const SmcVpl& v : still.state) CHECK(v.flags == 0u);
    const Validated moved = run_validate(s, state, 4, true);
    CHECK(moved.valid == std::vector<uint32_t>{1u, 0u, 0u, 0u});
    CHECK(moved.invalid_list == std::vector<uint32_t>{1u, 2u, 3u});
    for (uint32_t i = 0; i < 4; ++i) {
        CAPTURE(i);
        const bool dead = i == 1 || i == 2;
        CHECK(moved.state[i].flags == (dead ? 4u : 0u));  // kSmcDead
        CHECK(moved.state[i].radiosity.x == (dead ? 0.0f : 1.0f));
        CHECK(moved.state[i].choice_radiosity.z == (dead ? 0.0f : 3.0f));
    }
}

TEST_CASE("smc validate: every VPL invalid, and an empty set") {
    std::vector<SmcVpl> hidden;
    for (int i = 0; i < 70; ++i) {  // more than one workgroup
        hidden.push_back(with_anchor({-0.4 + 0.01 * i, 0.1 * std::sin(double(i)), 0.0}, {0.0, 0.0, 1.0}));
    }
    CHECK(check_validate(hidden, 70) == 70);
    CHECK(check_validate(hidden, 0) == 0);
}

TEST_CASE("smc validate: the invalid list stays in index order over several chunks of the compaction") {
    // 600 VPLs (three 256-wide chunks): every third anchor is seen beside the plate's shadow
    // (which ends at |x| = 0.83 on the floor), the others hidden under the plate.
    std::vector<SmcVpl> mixed;
    for (int i = 0; i < 600; ++i) {
        const double y = 0.1 * std::sin(double(i));
        mixed.push_back(i % 3 == 0 ? with_anchor({1.0 + 0.001 * i, y, 0.0}, {0.0, 0.0, 1.0})
                                   : with_anchor({-0.4 + 0.001 * i, y, 0.0}, {0.0, 0.0, 1.0}));
    }
    CHECK(check_validate(mixed, 600) == 400);
    CHECK(check_validate(mixed, 300) == 200);
}

TEST_CASE("smc revalidate: exactly the VPLs some camera point draws and sees are claimed, once") {
    const RevalidateScene s;
    std::vector<uint32_t> invalid_list;
    for (uint32_t i = 0; i < s.vpls.size(); ++i) {
        if (i % 4 != 3) invalid_list.push_back(i);  // VPLs 3, 7, 11, 15 stay valid
    }
    for (const uint32_t round : {0u, 1u}) {
        CAPTURE(round);
        // Few tries: some seen VPLs are never drawn, so the reference's draws decide.
        const uint32_t few = check_revalidate(s, invalid_list, 1, 9, 4, {round});
        CHECK(few > 0);
        const uint32_t many = check_revalidate(s, invalid_list, 16, 9, 4, {round});
        CHECK(many >= few);
    }
    // Both rounds in turn, as an update runs them: the second claims only what the first left.
    CHECK(check_revalidate(s, invalid_list, 1, 9, 4, {0u, 1u}) >= check_revalidate(s, invalid_list, 1, 9, 4, {0u}));
    CHECK(check_revalidate(s, {}, 16, 9, 4, {0u}) == 0);               // nothing invalid: nothing to do
    CHECK(check_revalidate(s, {0u, 3u, 6u}, 8, 2, 1, {0u, 1u}) == 0);  // only hidden VPLs: none claimed
}
