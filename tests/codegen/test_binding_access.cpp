// The generated kBindingAccess of a few kit shaders against their GLSL qualifiers: what a foreign
// frame graph reads to place its barriers (codegen reflects SPIR-V NonWritable / NonReadable).

#include "vplkit/shaders/build_sst.hpp"
#include "vplkit/shaders/exact_gi.hpp"
#include "vplkit/shaders/sst_gi.hpp"

#include <doctest/doctest.h>

#include <cstddef>

namespace {

using vplkit::shaders::Access;

// The access of binding number `binding` in a shader's tables.
template <size_t N>
Access binding_access(const VkDescriptorSetLayoutBinding (&layout)[N], const Access (&access)[N], uint32_t binding) {
    for (size_t i = 0; i < N; ++i) {
        if (layout[i].binding == binding) return access[i];
    }
    FAIL("no binding " << binding);
    return Access::read;
}

}  // namespace

TEST_CASE("binding access: readonly, writeonly and read-write bindings of kit shaders") {
    namespace sst = vplkit::shaders::sst_gi;
    CHECK(binding_access(sst::kSetLayoutBindings, sst::kBindingAccess, sst::kBindingSstNodes) == Access::read);
    CHECK(binding_access(sst::kSetLayoutBindings, sst::kBindingAccess, sst::kBindingGbufferPosition) == Access::read);
    CHECK(binding_access(sst::kSetLayoutBindings, sst::kBindingAccess, sst::kBindingIndirect) == Access::write);
    CHECK(binding_access(sst::kSetLayoutBindings, sst::kBindingAccess, sst::kBindingGiCounters) == Access::read_write);
    namespace exact = vplkit::shaders::exact_gi;
    // exact_gi adds each chunk onto the image: read and written.
    CHECK(binding_access(exact::kSetLayoutBindings, exact::kBindingAccess, exact::kBindingIndirect) ==
          Access::read_write);
    CHECK(binding_access(exact::kSetLayoutBindings, exact::kBindingAccess, exact::kBindingVpls) == Access::read);
    namespace build = vplkit::shaders::build_sst;
    CHECK(binding_access(build::kSetLayoutBindings, build::kBindingAccess, build::kBindingLeaves) == Access::read);
    CHECK(binding_access(build::kSetLayoutBindings, build::kBindingAccess, build::kBindingNodes) == Access::read_write);
}
