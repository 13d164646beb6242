#pragma once
// Both trees the samplers read, over `count` VPLs sorted into leaf order (vpl_trees.hpp builds
// them; a caller with its own build passes its own buffers):
//   leaves      Vpl[leaf_count], sorted; index >= count is bogus padding (all zero)
//   light_tree  LightTreeNode[2 leaf_count - 1] (light_tree.hpp), read by rtslc
//   sst         SstNode[sst_node_count(count)] (sst.hpp), read by sst and hybrid

#include "vplkit/views.hpp"

#include <cstdint>
#include <type_traits>

namespace vplkit::stages {

// One definition for views (VplTreeBuffers, what the samplers take) and owned buffers (the
// runtime's VplTrees, vplkit/vpl_trees.hpp): a set of buffers that convert to BufferView converts
// to the views.
template <class BufferT>
struct VplTreeSet {
    uint32_t count = 0;       // real VPLs
    uint32_t leaf_count = 0;  // leaf_count(count): a power of two
    BufferT leaves;           // Vpl[leaf_count], sorted; index >= count is bogus padding
    BufferT light_tree;       // LightTreeNode[2 leaf_count - 1] (light_tree.hpp)
    BufferT sst;              // SstNode[sst_node_count(count)] (sst.hpp)

    operator VplTreeSet<BufferView>() const requires(!std::is_same_v<BufferT, BufferView>) {
        return {count, leaf_count, leaves, light_tree, sst};
    }
};
using VplTreeBuffers = VplTreeSet<BufferView>;

}  // namespace vplkit::stages
