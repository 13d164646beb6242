// smc_vpls.comp (Alg. 1 line 19): each VPL of Y keeps its new density and intensity and becomes a
// Vpl at its position and normal with flux B(y) / (I p(y)) = B(y) x the area it stands for
// (eq. 5 with eq. 7).
// - On a hand-made density buffer: exactly (a float product; the reference rounds the double
//   product to float, which is the correctly rounded float product), for the first |Y| slots
//   only; slots past |Y| keep what they held. Fails if a field is copied from the wrong slot,
//   the flux uses another density entry, or a slot past |Y| is written.
// - After the real kNN pass (add_smc_density_pass, k = 3): flux = B / (|Y| p) with p = (k + 1/2)
//   / (|Y| pi r_k^2) from a double brute-force kNN (1e-4 relative: float distances).
// - |Y| = 0 writes nothing.

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/smc_vpls.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/smc.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

namespace {

using vplkit::shaders::SmcCounters;
using vplkit::shaders::SmcVpl;
using vplkit::shaders::Vpl;
using Vec4 = std::array<float, 4>;

vplkit::Buffer make(size_t bytes, const char* name) {
    return vplkit::Buffer::create(vplkit::test::context(), std::max<size_t>(bytes, 16),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
}

std::vector<SmcVpl> random_state(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<SmcVpl> state(count);
    for (SmcVpl& v : state) {
        v = SmcVpl{};
        v.position = {unit(rng), unit(rng), 0.0f};
        v.normal = {0.0f, 0.0f, 1.0f};
        v.radiosity = {unit(rng), unit(rng), unit(rng)};
        v.choice_radiosity = v.radiosity;
        v.seed = uint32_t(rng());
    }
    return state;
}

struct Written {
    std::vector<SmcVpl> state;
    std::vector<Vpl> vpls;
};

// Runs smc_vpls over `state` (|Y| = vpl_count) with `density`, or with the kNN densities of
// add_smc_density_pass (k neighbours) when `density` is empty.
Written run(const std::vector<SmcVpl>& state, uint32_t vpl_count, const std::vector<Vec4>& density, uint32_t k,
            std::vector<Vec4>* density_out = nullptr) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t budget = uint32_t(state.size());
    auto state_buffer = make(budget * sizeof(SmcVpl), "state");
    auto density_buffer = make(budget * sizeof(Vec4), "vpl density");
    auto vpl_buffer = make(budget * sizeof(Vpl), "vpls");
    auto counter_buffer = make(sizeof(SmcCounters), "counters");
    state_buffer.upload(state);
    std::vector<Vpl> before(budget, Vpl{});
    for (Vpl& v : before) v.flux = {-1.0f, -1.0f, -1.0f};
    vpl_buffer.upload(before);
    SmcCounters counters{};
    counters.vpl_count = vpl_count;
    counter_buffer.upload(std::vector<SmcCounters>{counters});
    vplkit::PassList passes("smc vpls test");
    std::optional<vplkit::GpuBvh> bvh;  // held until the passes ran
    if (density.empty()) {
        // The unit square the points lie on: scene scale 1; eq. 7's whole disc (no surface samples).
        const std::vector<glm::vec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
        bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(square));
        vplkit::stages::add_smc_density_pass(ctx, passes, *bvh, state_buffer, state_buffer, density_buffer,
                                             counter_buffer, budget, k, true, 0);
    } else {
        density_buffer.upload(density);
    }
    namespace shader = vplkit::shaders::smc_vpls;
    const auto& pipeline = ctx.pipeline<shader::Pipeline>();
    shader::Bindings b;
    b.state = state_buffer.descriptor();
    b.density = density_buffer.descriptor();
    b.vpls = vpl_buffer.descriptor();
    b.counters = counter_buffer.descriptor();
    shader::Push push{};
    push.budget = budget;
    passes.add("smc vpls", vplkit::stages::binding_uses<shader::Module>(b, {}),
               [&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, b, push, budget); });
    passes.run(ctx);
    if (density_out) *density_out = density_buffer.download<Vec4>(budget);
    return {state_buffer.download<SmcVpl>(budget), vpl_buffer.download<Vpl>(budget)};
}

}  // namespace

TEST_CASE("smc vpls: position, normal, flux = B x area and the new density, for the VPLs of Y only") {
    const uint32_t budget = 24, count = 17;
    const auto state = random_state(budget, 1);
    std::vector<Vec4> density(budget);
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> unit(0.1f, 10.0f);
    for (Vec4& d : density) d = {unit(rng), unit(rng), unit(rng), 0.0f};
    const Written w = run(state, count, density, 1);
    for (uint32_t i = 0; i < budget; ++i) {
        CAPTURE(i);
        if (i >= count) {
            CHECK(w.vpls[i].flux.x == -1.0f);  // past |Y|: not written
            CHECK(w.state[i].pdf == state[i].pdf);
            continue;
        }
        CHECK(w.state[i].pdf == density[i][0]);
        CHECK(w.state[i].intensity == density[i][1]);
        CHECK(w.state[i].seed == state[i].seed);
        CHECK(w.vpls[i].position.x == state[i].position.x);
        CHECK(w.vpls[i].position.y == state[i].position.y);
        CHECK(w.vpls[i].normal.z == state[i].normal.z);
        CHECK(w.vpls[i].flux.x == float(double(state[i].radiosity.x) * density[i][2]));
        CHECK(w.vpls[i].flux.y == float(double(state[i].radiosity.y) * density[i][2]));
        CHECK(w.vpls[i].flux.z == float(double(state[i].radiosity.z) * density[i][2]));
    }
    const Written empty = run(state, 0, density, 1);
    for (const Vpl& v : empty.vpls) CHECK(v.flux.x == -1.0f);
}

TEST_CASE("smc vpls: after the kNN pass a VPL's flux is B / (|Y| p), p by eq. 7 in double") {
    const uint32_t budget = 64, count = 60, k = 3;
    const auto state = random_state(budget, 3);
    const Written w = run(state, count, {}, k);
    for (uint32_t i = 0; i < count; ++i) {
        std::vector<double> d2;
        for (uint32_t j = 0; j < count; ++j) {
            if (j == i) continue;
            const double dx = double(state[j].position.x) - state[i].position.x;
            const double dy = double(state[j].position.y) - state[i].position.y;
            d2.push_back(dx * dx + dy * dy);
        }
        std::nth_element(d2.begin(), d2.begin() + (k - 1), d2.end());
        const double pdf = (k + 0.5) / (count * std::numbers::pi * d2[k - 1]);
        const double area = 1.0 / (count * pdf);
        CAPTURE(i);
        CHECK(w.state[i].pdf == doctest::Approx(pdf).epsilon(1e-4));
        CHECK(w.vpls[i].flux.x == doctest::Approx(state[i].radiosity.x * area).epsilon(1e-4));
        CHECK(w.vpls[i].flux.z == doctest::Approx(state[i].radiosity.z * area).epsilon(1e-4));
        // Eq. 6: intensity = lum(B) / p, with B the estimate that chose it.
        const double lum = 0.2126 * state[i].choice_radiosity.x + 0.7152 * state[i].choice_radiosity.y +
                           0.0722 * state[i].choice_radiosity.z;
        CHECK(w.state[i].intensity == doctest::Approx(lum / pdf).epsilon(1e-4));
    }
}
