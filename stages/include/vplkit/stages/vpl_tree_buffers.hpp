#pragma once
// Both trees the samplers read, over `count` VPLs sorted into leaf order (vpl_trees.hpp builds
// them; a caller with its own build passes its own buffers):
//   leaves      Vpl[leaf_count], sorted; index >= count is bogus padding (all zero)
//   light_tree  LightTreeNode[2 leaf_count - 1] (light_tree.hpp), read by rtslc
//   sst         SstNode[sst_node_count(count)] (sst.hpp), read by sst and hybrid

#include "vplkit/stages/views.hpp"

#include <cstdint>

namespace vplkit::stages {

struct VplTreeBuffers {
    uint32_t count = 0;       // real VPLs
    uint32_t leaf_count = 0;  // leaf_count(count): a power of two
    BufferView leaves;
    BufferView light_tree;
    BufferView sst;
};

}  // namespace vplkit::stages
