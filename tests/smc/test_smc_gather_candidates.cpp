// smc_gather_candidates.comp (Alg. 1 line 6): after the resampling sort, the first `budget`
// pool entries that carry a key are the candidates, each the hit its value names, with a seed of
// its own for its radiosity estimate. Checked exactly on hand-made sorted pools: which hits
// become candidates, in which slots, their count, that unkeyed entries and the slots past the
// count stay untouched, and that the seeds differ between candidates and between updates (an
// estimate shared by two candidates, or repeated every update, would correlate their choices).
// Fails if an unkeyed entry slips in, a keyed one is lost, a record is copied from the wrong hit
// or a seed repeats. Hard cases: no keyed entry at all, a pool smaller than the budget.
// (The keys' weighting, which hits the sort puts first, is tested with the camera rays.)

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/smc_gather_candidates.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <set>
#include <vector>

namespace {

using vplkit::shaders::SmcCounters;
using vplkit::shaders::SmcVpl;

constexpr uint32_t kNoKey = 0xffffffffu;

vplkit::Buffer make(size_t bytes, const char* name) {
    return vplkit::Buffer::create(vplkit::test::context(), std::max<size_t>(bytes, 16),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
}

struct Gathered {
    uint32_t count = 0;
    std::vector<SmcVpl> candidates;
};

// A pool of `pool` hits (hit h at x = h), sorted: `keyed` entries with keys first (their values
// a permutation of the hits), the rest unkeyed.
Gathered gather(uint32_t pool, uint32_t keyed, uint32_t budget, uint32_t seed, uint32_t iteration,
                std::vector<uint32_t>* values_out = nullptr) {
    vplkit::Context& ctx = vplkit::test::context();
    std::vector<SmcVpl> hits(pool);
    for (uint32_t h = 0; h < pool; ++h) {
        hits[h] = SmcVpl{};
        hits[h].position = {float(h), 2.0f, 3.0f};
        hits[h].normal = {0.0f, 1.0f, 0.0f};
        hits[h].triangle = 100u + h;
        hits[h].anchor = {float(h), 0.0f, 0.0f};
        hits[h].flags = 3u;
    }
    std::vector<uint64_t> keys(pool, kNoKey);
    std::vector<uint32_t> values(pool);
    for (uint32_t e = 0; e < pool; ++e) {
        values[e] = (e * 7u + 3u) % pool;          // a permutation (7 is prime to the pools used)
        if (e < keyed) keys[e] = 0x3f000000u + e;  // sorted, finite floats' bits
    }
    if (values_out) *values_out = values;
    std::vector<SmcVpl> sentinel(budget, SmcVpl{});
    for (SmcVpl& s : sentinel) s.position = {-7.0f, -7.0f, -7.0f};
    auto hit_buffer = make(pool * sizeof(SmcVpl), "hits");
    auto key_buffer = make(pool * 8, "pool keys");
    auto value_buffer = make(pool * 4, "pool values");
    auto candidate_buffer = make(budget * sizeof(SmcVpl), "candidates");
    auto counter_buffer = make(sizeof(SmcCounters), "counters");
    hit_buffer.upload(hits);
    key_buffer.upload(keys);
    value_buffer.upload(values);
    candidate_buffer.upload(sentinel);
    counter_buffer.upload(std::vector<SmcCounters>{SmcCounters{}});

    namespace shader = vplkit::shaders::smc_gather_candidates;
    const auto& pipeline = ctx.pipeline<shader::Pipeline>();
    shader::Bindings b;
    b.keys = key_buffer.descriptor();
    b.values = value_buffer.descriptor();
    b.hits = hit_buffer.descriptor();
    b.candidates = candidate_buffer.descriptor();
    b.counters = counter_buffer.descriptor();
    shader::Push push{};
    push.budget = budget;
    push.pool_count = pool;
    push.seed = seed;
    push.iteration = iteration;
    vplkit::PassList passes("smc gather candidates test");
    passes.add("smc gather candidates", vplkit::stages::binding_uses<shader::Module>(b, {}),
               [&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, b, push, budget); });
    passes.run(ctx);
    return {counter_buffer.download<SmcCounters>(1)[0].candidate_count, candidate_buffer.download<SmcVpl>(budget)};
}

// Candidate slots [0, count) hold hits values[c]; the rest the sentinel.
void check_candidates(const Gathered& g, const std::vector<uint32_t>& values, uint32_t count) {
    REQUIRE(g.count == count);
    std::set<uint32_t> seeds;
    for (uint32_t c = 0; c < g.candidates.size(); ++c) {
        CAPTURE(c);
        if (c >= count) {
            CHECK(g.candidates[c].position.x == -7.0f);
            continue;
        }
        CHECK(g.candidates[c].position.x == float(values[c]));
        CHECK(g.candidates[c].triangle == 100u + values[c]);
        CHECK(g.candidates[c].anchor.x == float(values[c]));
        CHECK(g.candidates[c].flags == 3u);
        seeds.insert(g.candidates[c].seed);
    }
    CHECK(seeds.size() == count);
}

}  // namespace

TEST_CASE("smc gather candidates: the keyed head of the sorted pool, up to the budget") {
    std::vector<uint32_t> values;
    check_candidates(gather(20, 5, 8, 11, 0, &values), values, 5);   // fewer keyed than the budget
    check_candidates(gather(20, 12, 8, 11, 0, &values), values, 8);  // more: the budget's worth
    check_candidates(gather(3, 3, 8, 11, 0, &values), values, 3);    // the pool is smaller than the budget
    check_candidates(gather(20, 0, 8, 11, 0, &values), values, 0);   // no hit at all: no candidate
}

TEST_CASE("smc gather candidates: the seeds change with the update and the seed") {
    const Gathered a = gather(40, 16, 16, 11, 0);
    const Gathered b = gather(40, 16, 16, 11, 1);
    const Gathered c = gather(40, 16, 16, 12, 0);
    const Gathered again = gather(40, 16, 16, 11, 0);
    std::set<uint32_t> all;
    for (uint32_t i = 0; i < 16; ++i) {
        CHECK(a.candidates[i].seed == again.candidates[i].seed);  // deterministic for a seed
        all.insert(a.candidates[i].seed);
        all.insert(b.candidates[i].seed);
        all.insert(c.candidates[i].seed);
    }
    CHECK(all.size() == 48);
}
