// Alg. 1 lines 9-17 (the SMC paper sec. 3.2.5), shader by shader, exactly:
// - smc_selection_keys.comp: Y's keys are its intensities' bits (ascending), the candidates' the
//   bits' complement (strongest first); empty slots, and candidates without light (0, -0, < 0,
//   NaN, inf), get kSmcNoKey (VPLs without light key 0: the weakest). Fails if a key is off by one bit or a dark
//   candidate gets a key.
// - smc_select.comp, on keys sorted here: M_strong, M_min, the removed slots (invalid weakest
//   first, at most M_max, then weak valid ones up to M_min), the moves (freed slots first, then
//   the empty ones, strongest candidate first) and the counters, against smc_select of
//   tests/reference/smc_reference.cpp. Fails on any different slot, candidate, order or count.
//   Hard cases: the first update (Y empty), no candidates, every VPL invalid, budget 1, fewer
//   candidates than invalid VPLs, a partly filled Y.
// - smc_replace.comp: each move's candidate lands in its slot with a new seed (its rendering
//   estimate's stream), valid; every other slot untouched.
// Intensities are distinct floats (the reference breaks no ties), converted to double exactly.

#include "smc_reference.hpp"
#include "brsm_reference.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/smc_replace.hpp"
#include "vplkit/shaders/smc_select.hpp"
#include "vplkit/shaders/smc_selection_keys.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <vector>

namespace {

using vplkit::shaders::SmcCounters;
using vplkit::shaders::SmcVpl;
namespace shaders = vplkit::shaders;

constexpr uint32_t kNoKey = 0xffffffffu;

vplkit::Buffer make(size_t bytes, const char* name) {
    return vplkit::Buffer::create(vplkit::test::context(), std::max<size_t>(bytes, 16),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
}

template <typename T>
vplkit::Buffer upload(const std::vector<T>& items, size_t count, const char* name) {
    auto buffer = make(count * sizeof(T), name);
    std::vector<T> padded = items;
    padded.resize(std::max<size_t>(count, 1));
    buffer.upload(padded);
    return buffer;
}

// `count` distinct positive floats in [lo, hi), shuffled.
std::vector<float> distinct_intensities(uint32_t count, float lo, float hi, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(lo, hi);
    std::set<float> values;
    while (values.size() < count) values.insert(unit(rng));
    std::vector<float> out(values.begin(), values.end());
    std::shuffle(out.begin(), out.end(), rng);
    return out;
}

// ---- smc_selection_keys.comp ----

struct Keys {
    std::vector<uint64_t> vpl_keys, candidate_keys;
    std::vector<uint32_t> vpl_values, candidate_values;
};

Keys run_selection_keys(const std::vector<float>& vpl_intensity, const std::vector<float>& candidate_intensity,
                        uint32_t budget) {
    vplkit::Context& ctx = vplkit::test::context();
    std::vector<SmcVpl> state(budget, SmcVpl{});
    for (size_t i = 0; i < vpl_intensity.size(); ++i) state[i].intensity = vpl_intensity[i];
    std::vector<std::array<float, 4>> density(budget, {0.0f, 0.0f, 0.0f, 0.0f});
    for (size_t c = 0; c < candidate_intensity.size(); ++c) density[c] = {1.0f, candidate_intensity[c], 0.0f, 0.0f};
    SmcCounters counters{};
    counters.vpl_count = uint32_t(vpl_intensity.size());
    counters.candidate_count = uint32_t(candidate_intensity.size());
    auto state_buffer = upload(state, budget, "state");
    auto density_buffer = upload(density, budget, "candidate density");
    auto counter_buffer = upload(std::vector<SmcCounters>{counters}, 1, "counters");
    auto vpl_keys = make(budget * 8, "vpl keys");
    auto vpl_values = make(budget * 4, "vpl values");
    auto candidate_keys = make(budget * 8, "candidate keys");
    auto candidate_values = make(budget * 4, "candidate values");

    namespace shader = shaders::smc_selection_keys;
    const auto& pipeline = ctx.pipeline<shader::Pipeline>();
    shader::Bindings b;
    b.state = state_buffer.descriptor();
    b.candidate_density = density_buffer.descriptor();
    b.vpl_keys = vpl_keys.descriptor();
    b.vpl_values = vpl_values.descriptor();
    b.candidate_keys = candidate_keys.descriptor();
    b.candidate_values = candidate_values.descriptor();
    b.counters = counter_buffer.descriptor();
    shader::Push push{};
    push.budget = budget;
    vplkit::PassList passes("smc selection keys test");
    passes.add("smc selection keys", vplkit::stages::binding_uses<shader::Module>(b, {}),
               [&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, b, push, budget); });
    passes.run(ctx);
    return {vpl_keys.download<uint64_t>(budget), candidate_keys.download<uint64_t>(budget),
            vpl_values.download<uint32_t>(budget), candidate_values.download<uint32_t>(budget)};
}

// ---- smc_select.comp ----

struct Selected {
    SmcCounters counters{};
    std::vector<std::pair<uint32_t, uint32_t>> moves;
};

// The keys smc_selection_keys writes, sorted (ascending by key; a stable sort keeps equal keys
// in index order, as the kit's sorts do): computed here from the definition, so the select test
// does not depend on the keys shader.
std::pair<std::vector<uint64_t>, std::vector<uint32_t>> sorted_keys(const std::vector<uint64_t>& keys) {
    std::vector<uint32_t> order(keys.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
    std::vector<uint64_t> sorted;
    for (uint32_t i : order) sorted.push_back(keys[i]);
    return {sorted, order};
}

Selected run_select(const std::vector<float>& vpl_intensity, const std::vector<uint32_t>& valid,
                    const std::vector<float>& candidate_intensity, uint32_t budget, uint32_t max_moves,
                    float quantile) {
    vplkit::Context& ctx = vplkit::test::context();
    std::vector<uint64_t> vpl_keys(budget, kNoKey), candidate_keys(budget, kNoKey);
    for (size_t i = 0; i < vpl_intensity.size(); ++i) vpl_keys[i] = std::bit_cast<uint32_t>(vpl_intensity[i]);
    for (size_t c = 0; c < candidate_intensity.size(); ++c) {
        candidate_keys[c] = candidate_intensity[c] > 0.0f ? ~std::bit_cast<uint32_t>(candidate_intensity[c]) : kNoKey;
    }
    const auto [vk, vv] = sorted_keys(vpl_keys);
    const auto [ck, cv] = sorted_keys(candidate_keys);
    std::vector<uint32_t> valid_padded = valid;
    valid_padded.resize(budget, 0u);
    SmcCounters counters{};
    counters.vpl_count = uint32_t(vpl_intensity.size());
    auto vpl_key_buffer = upload(vk, budget, "vpl keys");
    auto vpl_value_buffer = upload(vv, budget, "vpl values");
    auto candidate_key_buffer = upload(ck, budget, "candidate keys");
    auto candidate_value_buffer = upload(cv, budget, "candidate values");
    auto valid_buffer = upload(valid_padded, budget, "valid");
    auto moves = make(budget * 8, "moves");
    auto counter_buffer = upload(std::vector<SmcCounters>{counters}, 1, "counters");

    namespace shader = shaders::smc_select;
    const auto& pipeline = ctx.pipeline<shader::Pipeline>();
    shader::Bindings b;
    b.vpl_keys = vpl_key_buffer.descriptor();
    b.vpl_values = vpl_value_buffer.descriptor();
    b.candidate_keys = candidate_key_buffer.descriptor();
    b.candidate_values = candidate_value_buffer.descriptor();
    b.valid = valid_buffer.descriptor();
    b.moves = moves.descriptor();
    b.counters = counter_buffer.descriptor();
    shader::Push push{};
    push.budget = budget;
    push.max_moves = max_moves;
    push.quantile = quantile;
    vplkit::PassList passes("smc select test");
    passes.add("smc select", vplkit::stages::binding_uses<shader::Module>(b, {}),
               [&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, b, push, 1u); });
    passes.run(ctx);
    Selected s;
    s.counters = counter_buffer.download<SmcCounters>(1)[0];
    const auto pairs = moves.download<std::array<uint32_t, 2>>(budget);
    for (uint32_t m = 0; m < s.counters.move_count && m < budget; ++m) s.moves.push_back({pairs[m][0], pairs[m][1]});
    return s;
}

// Runs select and compares everything with the reference; returns the reference's answer.
vplkit::reference::SmcSelection check_select(const std::vector<float>& vpl_intensity,
                                             const std::vector<uint32_t>& valid,
                                             const std::vector<float>& candidate_intensity, uint32_t budget,
                                             uint32_t max_moves, float quantile = 0.95f) {
    const std::vector<double> vi(vpl_intensity.begin(), vpl_intensity.end());
    const std::vector<double> ci(candidate_intensity.begin(), candidate_intensity.end());
    const auto expected = vplkit::reference::smc_select(vi, valid, ci, budget, max_moves, quantile);
    const Selected got = run_select(vpl_intensity, valid, candidate_intensity, budget, max_moves, quantile);
    CHECK(got.counters.candidate_count == expected.candidates);
    CHECK(got.counters.strong_count == expected.strong);
    CHECK(got.counters.min_moves == expected.min_moves);
    CHECK(got.counters.still_invalid == expected.still_invalid);
    CHECK(got.counters.removed == expected.removed);
    CHECK(got.counters.move_count == expected.moves.size());
    CHECK(got.counters.vpl_count == expected.vpl_count);
    CHECK(got.moves == expected.moves);
    // What must hold whatever the rules: the budget, M_max, no slot filled twice.
    CHECK(got.counters.vpl_count <= budget);
    CHECK(got.counters.removed <= max_moves);
    std::set<uint32_t> slots;
    for (const auto& m : got.moves) slots.insert(m.first);
    CHECK(slots.size() == got.moves.size());
    return expected;
}

}  // namespace

TEST_CASE("smc selection keys: intensity bits ascending, complements for candidates, no key without light") {
    const uint32_t budget = 12;
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    // -0.0 has the sign bit: taken as a key, it would rank above every positive intensity.
    const std::vector<float> vpls = {3.5f, 0.25f, 0.0f, nan, 1e-20f, -2.0f, inf, 7.0f, -0.0f};
    const std::vector<float> candidates = {2.0f, 0.0f, 9.5f, nan, -1.0f, 1e-3f, inf, 0.5f, 4.0f, -0.0f};
    const Keys k = run_selection_keys(vpls, candidates, budget);
    auto light_bits = [](float v) -> uint32_t {  // a usable intensity's bits, else 0
        return (v > 0.0f && std::isfinite(v)) ? std::bit_cast<uint32_t>(v) : 0u;
    };
    for (uint32_t i = 0; i < budget; ++i) {
        CAPTURE(i);
        CHECK(k.vpl_values[i] == i);
        CHECK(k.candidate_values[i] == i);
        CHECK(k.vpl_keys[i] == (i < vpls.size() ? uint64_t(light_bits(vpls[i])) : uint64_t(kNoKey)));
        const uint32_t bits = i < candidates.size() ? light_bits(candidates[i]) : 0u;
        CHECK(k.candidate_keys[i] == (bits == 0u ? uint64_t(kNoKey) : uint64_t(~bits)));
    }
    // The orders the sorts then give: Y weakest first, candidates strongest first.
    CHECK(k.vpl_keys[4] < k.vpl_keys[1]);
    CHECK(k.vpl_keys[1] < k.vpl_keys[0]);
    CHECK(k.vpl_keys[0] < k.vpl_keys[7]);
    CHECK(k.candidate_keys[2] < k.candidate_keys[8]);
    CHECK(k.candidate_keys[8] < k.candidate_keys[0]);
    CHECK(k.candidate_keys[0] < k.candidate_keys[5]);
}

TEST_CASE("smc select: a full set with invalid VPLs and strong candidates") {
    const uint32_t budget = 64;
    const auto vpls = distinct_intensities(budget, 1.0f, 2.0f, 1);
    std::vector<uint32_t> valid(budget, 1u);
    for (uint32_t i : {3u, 17u, 40u, 41u, 63u}) valid[i] = 0u;
    // 40 candidates, a dozen above every VPL (strong), the rest spread over Y's range.
    auto candidates = distinct_intensities(28, 1.0f, 2.0f, 2);
    const auto strong = distinct_intensities(12, 2.5f, 3.0f, 3);
    candidates.insert(candidates.end(), strong.begin(), strong.end());
    const auto e = check_select(vpls, valid, candidates, budget, 16);
    CHECK(e.removed > 5);  // the invalid ones and weak valid ones: the case exercises both walks
    CHECK(e.still_invalid == 5);
    // M_max binds: fewer strong candidates allowed to move.
    check_select(vpls, valid, candidates, budget, 3);
}

TEST_CASE("smc select: the first update fills Y with the strongest candidates") {
    const uint32_t budget = 64;
    const auto few = distinct_intensities(30, 0.1f, 5.0f, 4);
    const auto e = check_select({}, {}, few, budget, 16);
    CHECK(e.vpl_count == 30);
    const auto many = distinct_intensities(budget, 0.1f, 5.0f, 5);
    std::vector<float> with_dark = many;
    with_dark[7] = 0.0f;  // a candidate without light never enters
    const auto full = check_select({}, {}, with_dark, budget, 16);
    CHECK(full.vpl_count == budget - 1);
}

TEST_CASE("smc select: no candidates, every VPL invalid, fewer candidates than invalid VPLs") {
    const uint32_t budget = 32;
    const auto vpls = distinct_intensities(budget, 1.0f, 2.0f, 6);
    std::vector<uint32_t> some_invalid(budget, 1u);
    for (uint32_t i = 0; i < 10; ++i) some_invalid[3 * i] = 0u;
    const auto none = check_select(vpls, some_invalid, {}, budget, 16);
    CHECK(none.removed == 0);
    CHECK(none.vpl_count == budget);

    const std::vector<uint32_t> all_invalid(budget, 0u);
    const auto candidates = distinct_intensities(20, 0.5f, 1.5f, 7);
    const auto all = check_select(vpls, all_invalid, candidates, budget, 8);
    CHECK(all.removed == 8);
    CHECK(all.still_invalid == budget);

    const auto three = distinct_intensities(3, 0.5f, 1.5f, 8);
    const auto short_of = check_select(vpls, some_invalid, three, budget, 16);
    CHECK(short_of.removed == 3);
    CHECK(short_of.vpl_count == budget);
}

TEST_CASE("smc select: budget 1 and a partly filled set") {
    check_select({1.0f}, {1u}, {2.0f}, 1, 16);  // stronger: replaces the one VPL
    const auto weaker = check_select({1.0f}, {1u}, {0.5f}, 1, 16);
    CHECK(weaker.removed == 0);
    const auto invalid = check_select({1.0f}, {0u}, {0.5f}, 1, 16);
    CHECK(invalid.removed == 1);

    const uint32_t budget = 64;
    const auto vpls = distinct_intensities(50, 1.0f, 2.0f, 9);
    std::vector<uint32_t> valid(50, 1u);
    valid[5] = valid[6] = 0u;
    const auto candidates = distinct_intensities(30, 1.5f, 3.0f, 10);
    const auto e = check_select(vpls, valid, candidates, budget, 4);
    CHECK(e.vpl_count == budget);  // the 14 empty slots fill at once, besides the replaced ones
}

TEST_CASE("smc replace: each move's candidate lands in its slot, valid, with a seed of its own") {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t budget = 16;
    std::vector<SmcVpl> candidates(budget), state(budget);
    for (uint32_t i = 0; i < budget; ++i) {
        candidates[i] = SmcVpl{};
        candidates[i].position = {float(i), 1.0f, 2.0f};
        candidates[i].seed = 1000u + i;
        candidates[i].triangle = 50u + i;
        candidates[i].choice_radiosity = {0.5f * i, 0.0f, 1.0f};
        state[i] = SmcVpl{};
        state[i].position = {-1.0f, -1.0f, float(i)};  // untouched slots keep this
        state[i].seed = 7u;
    }
    const std::vector<std::array<uint32_t, 2>> moves = {{4, 9}, {11, 0}, {2, 15}};
    std::vector<uint32_t> valid(budget, 0u);
    for (const uint32_t move_count : {0u, 3u}) {
        CAPTURE(move_count);
        SmcCounters counters{};
        counters.move_count = move_count;
        auto candidate_buffer = upload(candidates, budget, "candidates");
        auto move_buffer = upload(moves, budget, "moves");
        auto state_buffer = upload(state, budget, "state");
        auto valid_buffer = upload(valid, budget, "valid");
        auto counter_buffer = upload(std::vector<SmcCounters>{counters}, 1, "counters");
        namespace shader = shaders::smc_replace;
        const auto& pipeline = ctx.pipeline<shader::Pipeline>();
        shader::Bindings b;
        b.candidates = candidate_buffer.descriptor();
        b.moves = move_buffer.descriptor();
        b.state = state_buffer.descriptor();
        b.valid = valid_buffer.descriptor();
        b.counters = counter_buffer.descriptor();
        shader::Push push{};
        push.budget = budget;
        vplkit::PassList passes("smc replace test");
        passes.add("smc replace", vplkit::stages::binding_uses<shader::Module>(b, {}),
                   [&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, b, push, budget); });
        passes.run(ctx);
        const auto out = state_buffer.download<SmcVpl>(budget);
        const auto out_valid = valid_buffer.download<uint32_t>(budget);
        for (uint32_t slot = 0; slot < budget; ++slot) {
            CAPTURE(slot);
            const auto move =
                std::find_if(moves.begin(), moves.begin() + move_count, [&](const auto& m) { return m[0] == slot; });
            if (move == moves.begin() + move_count) {
                CHECK(out[slot].position.z == float(slot));
                CHECK(out[slot].seed == 7u);
                CHECK(out_valid[slot] == 0u);
                continue;
            }
            const SmcVpl& c = candidates[(*move)[1]];
            CHECK(out[slot].position.x == c.position.x);
            CHECK(out[slot].triangle == c.triangle);
            CHECK(out[slot].choice_radiosity.x == c.choice_radiosity.x);
            CHECK(out[slot].seed == vplkit::reference::pcg_hash(c.seed ^ 0x68bc21ebu));
            CHECK(out[slot].seed != c.seed);  // the rendering estimate's stream is not the choosing one's
            CHECK(out_valid[slot] == 1u);
        }
    }
}
