#pragma once
// From a VPL buffer to both trees the samplers read, in one pass list: keys (Morton + normal
// octant + id), sort, leaves gathered in sorted order with bogus padding, the RTSLC light tree
// and the stochastic substitute tree. The buffers stay alive with the VplTrees object.

#include "vplkit/buffer.hpp"
#include "vplkit/stages/element_count.hpp"
#include "vplkit/stages/light_tree.hpp"
#include "vplkit/stages/sort.hpp"
#include "vplkit/stages/sst.hpp"
#include "vplkit/stages/vpl_tree_buffers.hpp"

#include <cstdint>
#include <memory>

namespace vplkit {
class Context;
class PassList;
}  // namespace vplkit

namespace vplkit {

struct VplTreeOptions {
    stages::SortOptions sort;
    stages::LightTreeOptions light_tree;
    stages::SstOptions sst;
};

// The tags (StepList::set_tag) of the passes of each part of the build, for a frame graph that
// groups them.
struct VplTreeBuildTags {
    uint32_t sort = 0;  // keys, sort, gather leaves
    uint32_t light_tree = 0;
    uint32_t sst = 0;
};

// The trees' buffers, owned (stages/vpl_tree_buffers.hpp's VplTreeSet; converts to VplTreeBuffers).
struct VplTrees : stages::VplTreeSet<Buffer> {
    // The buffers for `count` VPLs (1..kMaxKeyedVpls); throws vplkit::Error otherwise.
    static VplTrees create(Context& context, uint32_t count, const VplTreeOptions& options = {});

    // Adds the passes that fill leaves, light_tree and sst from `vpls` (Vpl[count]): "vpl keys",
    // the sort's passes, "gather leaves", then "light tree leaves/levels" and "build sst" unless
    // the caller needs only one of the trees (a method reads one: rtslc the light tree, sst and
    // hybrid the SST).
    void add_build_passes(PassList& passes, const Buffer& vpls, bool light_tree = true, bool sst = true,
                          const VplTreeBuildTags& tags = {});
    // The same over the count a GPU pass wrote (ElementCount::on_gpu, its capacity this object's
    // `count`): the trees are those of the capacity with every VPL past the count bogus padding,
    // so a frame samples VPLs it never read back.
    void add_build_passes(PassList& passes, const Buffer& vpls, const stages::ElementCount& vpl_count,
                          bool light_tree = true, bool sst = true, const VplTreeBuildTags& tags = {});

private:
    struct Scratch;
    std::shared_ptr<Scratch> scratch_;  // keys, values, bounds, sorter, SST counters
    Context* context_ = nullptr;
    VplTreeOptions options_;
};

}  // namespace vplkit
