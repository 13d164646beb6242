// build_sst.comp's suitability flags on surfaces laid out as a Morton sort would (flat, noisy,
// bent), at the thesis and the paper thresholds, and sigma_max as a length in world units; against
// the double reference within its bound (sst_build_check.hpp; the tolerances: test_build_sst.cpp).
#include "sst_build_check.hpp"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace vplkit::sst_test;

TEST_CASE("sst: suitability flags at the thesis and the paper thresholds") {
    SUBCASE("two VPLs: nu = 0.6 between the thresholds") {
        const Scene scene =
            padded({make_vpl({0, 0, 0}, {0, 0, 1}, {1, 1, 1}), make_vpl({0, 0, 0}, {0.8f, 0, 0.6f}, {1, 1, 1})});
        const auto thesis = build_on_gpu(scene, kThesis);
        const auto paper = build_on_gpu(scene, kPaper);
        CHECK(thesis[0].nu == doctest::Approx(0.6).epsilon(1e-6));
        CHECK((thesis[0].flags & 1u) == 0u);  // 0.6 < 0.7
        CHECK((paper[0].flags & 1u) == 1u);   // 0.6 >= 0.5
    }
    SUBCASE("two VPLs: sigma_z = 0.2 between the thresholds") {
        // equal weights 0.4 apart along the normal: var_z = a b d^2 = 0.04
        const Scene scene =
            padded({make_vpl({0, 0, 0}, {0, 0, 1}, {1, 1, 1}), make_vpl({0, 0, 0.4f}, {0, 0, 1}, {1, 1, 1})});
        const auto thesis = build_on_gpu(scene, kThesis);
        const auto paper = build_on_gpu(scene, kPaper);
        CHECK(thesis[0].variance.z == doctest::Approx(0.04).epsilon(1e-6));
        CHECK(thesis[0].variance.x == 0.0f);
        CHECK(thesis[0].variance.y == 0.0f);
        CHECK((thesis[0].flags & 1u) == 1u);  // 0.2 <= 0.3
        CHECK((paper[0].flags & 1u) == 0u);   // 0.2 > 0.1
    }
    SUBCASE("a floor and a bent sheet") {
        std::vector<Vpl> vpls = patch(4, 0.1, 0.0, 0.005, 1, {0.0, 0.0, 0.0});
        const std::vector<Vpl> bent = patch(4, 0.1, 1.0, 0.02, 2, {5.0, 0.0, 0.0});
        vpls.insert(vpls.end(), bent.begin(), bent.end());
        std::vector<Vpl> wall = patch(3, 0.1, 0.0, 0.01, 3, {0.0, 0.0, 0.0});
        for (Vpl& v : wall) {  // a wall x = -1 facing +x
            v.position = {-1.0f, v.position.y, v.position.x};
            v.normal = {1.0f, 0.0f, 0.0f};
        }
        vpls.insert(vpls.end(), wall.begin(), wall.end());  // 576 VPLs
        const Scene scene = padded(vpls);
        const auto thesis_nodes = build_on_gpu(scene, kThesis);
        const auto paper_nodes = build_on_gpu(scene, kPaper);
        const Comparison thesis = compare_with_reference(scene, thesis_nodes, kThesis);
        const Comparison paper = compare_with_reference(scene, paper_nodes, kPaper);
        CHECK(thesis.ambiguous_flags <= thesis.nodes / 50);
        CHECK(paper.ambiguous_flags <= paper.nodes / 50);
        // Each set accepts some nodes and refuses others, and they disagree on some.
        CHECK(thesis.suitable > 0);
        CHECK(paper.suitable > 0);
        CHECK(thesis.suitable < thesis.nodes);
        CHECK(paper.suitable < paper.nodes);
        uint32_t differ = 0;
        for (size_t i = 0; i < thesis_nodes.size(); ++i) {
            differ += ((thesis_nodes[i].flags ^ paper_nodes[i].flags) & 1u) != 0u ? 1 : 0;
        }
        CHECK(differ > 0);
        // The whole floor (leaves 0..255, node 3) is flat: suitable at both; the root mixes the
        // floor with the wall and the sheet: at neither.
        CHECK((thesis_nodes[3].flags & 1u) == 1u);
        CHECK((paper_nodes[3].flags & 1u) == 1u);
        CHECK((thesis_nodes[0].flags & 1u) == 0u);
        CHECK((paper_nodes[0].flags & 1u) == 0u);
    }
}

TEST_CASE("sst: sigma_max is a length in world units") {
    // The floor + bent sheet + wall scene at 1e-3, 1 and 1e4 scale, 1000x its size away from the
    // origin. With sigma_max scaled along, the same nodes are suitable; with the unscaled 0.3
    // the small scene accepts every planar-enough node and the large one almost none.
    auto scene_at = [](double s) {
        const std::array<double, 3> far{1000 * s, -700 * s, 300 * s};
        std::vector<Vpl> vpls = patch(4, 0.1 * s, 0.0, 0.005 * s, 1, far);
        const std::vector<Vpl> bent = patch(4, 0.1 * s, 1.0 * s, 0.02 * s, 2, {far[0] + 5 * s, far[1], far[2]});
        vpls.insert(vpls.end(), bent.begin(), bent.end());
        return padded(vpls);
    };
    const Scene unit_scene = scene_at(1.0);
    const auto unit_nodes = build_on_gpu(unit_scene, kThesis);
    compare_with_reference(unit_scene, unit_nodes, kThesis);
    for (double s : {1e-3, 1e4}) {
        CAPTURE(s);
        const Scene scene = scene_at(s);
        const SstOptions scaled{0.7f, float(0.3 * s)};
        const auto nodes = build_on_gpu(scene, scaled);
        const Comparison c = compare_with_reference(scene, nodes, scaled);
        CHECK(c.ambiguous_flags <= c.nodes / 50);
        uint32_t same = 0;
        for (size_t i = 0; i < nodes.size(); ++i) same += (nodes[i].flags & 1u) == (unit_nodes[i].flags & 1u) ? 1 : 0;
        CHECK(same + c.ambiguous_flags >= nodes.size());
        CHECK((nodes[1].flags & 1u) == 1u);  // the whole floor (leaves 0..255)

        const auto unscaled = build_on_gpu(scene, kThesis);
        compare_with_reference(scene, unscaled, kThesis);
        CHECK((unscaled[1].flags & 1u) == (s < 1.0 ? 1u : 0u));
    }
}
