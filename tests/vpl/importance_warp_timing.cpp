// Times importance_mips + warp_samples on a 512x512 map (PassList GPU timings, median of 5 runs).
// Usage: importance_warp_timing [samples...]   (default: 4096 100000)

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/importance_warp.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
    std::vector<uint32_t> counts;
    for (int i = 1; i < argc; ++i) counts.push_back(uint32_t(std::strtoul(argv[i], nullptr, 10)));
    if (counts.empty()) counts = {4096, 100000};
    const uint32_t size = 512;
    auto ctx = vplkit::Context::create(vplkit::ContextOptions{});
    std::vector<float> map(size * size);
    for (uint32_t t = 0; t < map.size(); ++t) map[t] = float(1.0 + std::sin(0.01 * t));
    auto importance = vplkit::Buffer::create(*ctx, map.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                             vplkit::MemoryUse::device, "importance");
    auto mips = vplkit::Buffer::create(*ctx, vplkit::stages::importance_mip_floats(size) * 4,
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "mips");
    auto count =
        vplkit::Buffer::create(*ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "count");
    importance.upload(map);
    for (uint32_t n : counts) {
        auto samples = vplkit::Buffer::create(*ctx, uint64_t(n) * sizeof(vplkit::shaders::WarpedSample),
                                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "samples");
        std::vector<double> copy_ms, mip_ms, warp_ms;
        for (int run = 0; run < 5; ++run) {
            vplkit::PassList passes("importance warp timing");
            vplkit::stages::add_importance_mips_passes(*ctx, passes, importance, mips, size);
            vplkit::stages::add_warp_samples_pass(*ctx, passes, mips, samples, count, size, n, run);
            passes.run(*ctx);
            double c = 0, m = 0, w = 0;
            for (const auto& t : passes.timings()) {
                (t.name == "warp samples" ? w : t.name == "importance copy" ? c : m) += t.gpu_ms;
            }
            copy_ms.push_back(c);
            mip_ms.push_back(m);
            warp_ms.push_back(w);
        }
        std::sort(copy_ms.begin(), copy_ms.end());
        std::sort(mip_ms.begin(), mip_ms.end());
        std::sort(warp_ms.begin(), warp_ms.end());
        std::printf("%ux%u map, %u samples: copy %.3f ms, mips (9 levels) %.3f ms, warp %.3f ms (medians of 5)\n", size,
                    size, n, copy_ms[2], mip_ms[2], warp_ms[2]);
    }
    return 0;
}
