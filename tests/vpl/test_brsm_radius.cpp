// The capped 1/r^2 radius sampler of vplkit/brsm.glsl against its own pdf, through a test shader
// (shaders/radius_samples.comp): the pdf integrates to 1 over [0, max_radius] (midpoint rule on
// 2^16 cells; the pdf is piecewise smooth, so within 1e-4), and the samples of a regular u grid
// follow its CDF (Kolmogorov-Smirnov distance of the 2^16 samples against the pdf's integral,
// within 1e-3: a correct inverse CDF gives ~1/n plus the quadrature error).

#include "vplkit/brsm_test/radius_samples.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

TEST_CASE("brsm radius: the capped inverse-square sampler and its pdf are a pair") {
    namespace shader = vplkit::brsm_test::radius_samples;
    using Sample = vplkit::brsm_test::RadiusSample;
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t n = 1u << 16;
    for (auto [core, max_radius] : {std::pair{0.1f, 1.0f}, std::pair{0.02f, 10.0f}, std::pair{1.0f, 1.5f}}) {
        CAPTURE(core);
        CAPTURE(max_radius);
        auto results = vplkit::Buffer::create(ctx, n * sizeof(Sample), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                              vplkit::MemoryUse::device, "radius samples");
        const auto& pipeline = ctx.pipeline<shader::Pipeline>();
        vplkit::PassList passes("radius samples test");
        passes.add("radius samples", {vplkit::Use::write(results)}, [&](VkCommandBuffer cmd) {
            shader::Bindings b;
            b.results = results.descriptor();
            shader::Push push{};
            push.count = n;
            push.core = core;
            push.max_radius = max_radius;
            pipeline.dispatch(cmd, b, push, n);
        });
        passes.run(ctx);
        const auto samples = results.download<Sample>(n);

        // The pdf's CDF on the grid's cell edges, by the midpoint rule.
        const double dr = double(max_radius) / n;
        std::vector<double> cdf(n + 1, 0.0);
        for (uint32_t i = 0; i < n; ++i) cdf[i + 1] = cdf[i] + samples[i].pdf_at_grid * dr;
        CHECK(std::abs(cdf[n] - 1.0) < 1e-4);

        std::vector<double> radii;
        for (const Sample& s : samples) {
            REQUIRE(s.radius >= 0.0f);
            REQUIRE(s.radius <= max_radius * (1.0f + 1e-6f));
            radii.push_back(s.radius);
        }
        std::sort(radii.begin(), radii.end());
        double ks = 0;
        for (uint32_t k = 0; k < n; ++k) {
            // CDF at the sample, linear inside its cell.
            const double x = std::min(radii[k] / dr, double(n) - 1e-9);
            const auto cell = size_t(x);
            const double at = cdf[cell] + (cdf[cell + 1] - cdf[cell]) * (x - double(cell));
            ks = std::max({ks, std::abs(at - double(k) / n), std::abs(at - double(k + 1) / n)});
        }
        CAPTURE(ks);
        CHECK(ks < 1e-3);
    }
}
