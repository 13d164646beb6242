// Generated layouts vs offsets computed by hand from the GLSL rules (GL_KHR_vulkan_glsl,
// GLSL 4.60 section 7.6.2.2, VK_EXT_scalar_block_layout). The generated headers already
// static_assert their own numbers; this file checks those numbers are the right ones,
// written down independently.
//
// Rules used (N = 4 bytes, a float):
//   std430: scalar align N; vec2 align 2N; vec3/vec4 align 4N (vec3 size 3N);
//           array stride = element size rounded up to element alignment (no rounding to 16);
//           matrix = array of column vectors; struct align = max member align, size rounded
//           up to it.
//   std140: as std430, but array strides and struct alignments round up to 16 (vec4).
//   scalar: every member aligned to its component size; no rounding of arrays or structs.
#include <doctest/doctest.h>

#include <cstddef>
#include <type_traits>

#include "vplkit/fixtures/layout_only.hpp"
#include "vplkit/fixtures/roundtrip.hpp"
#include "vplkit/fixtures/spec_consts.hpp"

namespace fx = vplkit::fixtures;

TEST_CASE("std430 struct: vec3 + scalar packing - trailing padding to the array stride") {
    // TrapItem { vec3 position; float radius; vec3 normal; } : radius fills position's 4th slot.
    CHECK(offsetof(fx::TrapItem, position) == 0);
    CHECK(offsetof(fx::TrapItem, radius) == 12);
    CHECK(offsetof(fx::TrapItem, normal) == 16);  // vec3 aligned to 16
    // Members end at 28; the struct's 16-byte alignment makes the array stride 32, and the host
    // struct is padded to it so a std::vector<TrapItem> matches the buffer.
    CHECK(sizeof(fx::TrapItem) == 32);
    CHECK(sizeof(fx::TrapInner) == 16);
}

TEST_CASE("std430 block: every trap") {
    using T = fx::Std430Traps;
    CHECK(offsetof(T, v3) == 0);
    CHECK(offsetof(T, after_v3) == 12);  // a float right after a vec3 packs into its 4th slot
    CHECK(offsetof(T, v3_array) == 16);  // vec3[3]: align 16, stride 16 -> 16..64
    CHECK(sizeof(T::v3_array) == 48);
    CHECK(sizeof(T::v3_array[0]) == 16);  // padded element
    CHECK(offsetof(T, v2_array) == 64);   // vec2[3]: stride 8 in std430 -> 64..88
    CHECK(sizeof(T::v2_array) == 24);
    CHECK(offsetof(T, f_array) == 88);  // float[3]: stride 4 -> 88..100
    CHECK(offsetof(T, m3) == 112);      // mat3: align 16 -> 112, 3 columns of 16 -> 160
    CHECK(sizeof(T::m3) == 48);
    CHECK(offsetof(T, m4) == 160);    // mat4: 64 bytes -> 224
    CHECK(offsetof(T, m2x3) == 224);  // 2 columns of vec3, stride 16 -> 256
    CHECK(sizeof(T::m2x3) == 32);
    CHECK(offsetof(T, m3x2) == 256);  // 3 columns of vec2, stride 8 -> 280
    CHECK(sizeof(T::m3x2) == 24);
    CHECK(offsetof(T, m2) == 280);  // mat2 in std430: column stride 8 -> 296
    CHECK(sizeof(T::m2) == 16);
    CHECK(offsetof(T, u64) == 296);  // uint64: align 8
    CHECK(offsetof(T, i64) == 304);
    CHECK(offsetof(T, u64v2) == 320);  // u64vec2: align 16 -> 312 rounds up to 320
    CHECK(offsetof(T, flag) == 336);   // bool in a block: a 32-bit uint
    CHECK(offsetof(T, inner) == 352);  // struct align 16: 340 -> 352
    CHECK(offsetof(T, items) == 368);  // TrapItem[2], stride 32 -> 432
    CHECK(sizeof(T::items) == 64);
    CHECK(offsetof(T, tail) == 432);
    // Members end at 436; C++ rounds the struct to its 8-byte alignment (64-bit members):
    // explicit trailing padding.
    CHECK(sizeof(T) == 440);
    static_assert(std::is_same_v<decltype(T::flag), uint32_t>);
    static_assert(std::is_same_v<decltype(T::u64), uint64_t>);
    static_assert(std::is_same_v<decltype(T::i64), int64_t>);
}

TEST_CASE("std140 block: array and matrix strides round up to 16") {
    using T = fx::Std140Traps;
    CHECK(offsetof(T, v2_array) == 0);  // vec2[3]: stride 16 in std140 -> 0..48
    CHECK(sizeof(T::v2_array[0]) == 16);
    CHECK(offsetof(T, f_array) == 48);  // float[2]: stride 16 -> 48..80
    CHECK(sizeof(T::f_array) == 32);
    CHECK(offsetof(T, v3) == 80);
    CHECK(offsetof(T, after_v3) == 92);
    CHECK(offsetof(T, m3) == 96);   // mat3: 3 x 16 -> 144
    CHECK(offsetof(T, m2) == 144);  // mat2 in std140: column stride 16 -> 32 bytes
    CHECK(sizeof(T::m2) == 32);
    CHECK(offsetof(T, m2x3) == 176);  // 2 x 16 -> 208
    CHECK(offsetof(T, m3x2) == 208);  // vec2 columns, stride 16 in std140 -> 48 bytes
    CHECK(sizeof(T::m3x2) == 48);
    CHECK(offsetof(T, inner) == 256);  // struct align 16
    CHECK(offsetof(T, after_inner) == 272);
    CHECK(offsetof(T, u2) == 280);  // uvec2: align 8 -> 276 rounds up to 280
    CHECK(sizeof(T) == 288);
}

TEST_CASE("std140 two-dimensional array: a stride per dimension") {
    // FragParams { TrapInner inner; vec4 tint; float grid[2][3]; }
    using T = fx::FragParams;
    CHECK(offsetof(T, inner) == 0);
    CHECK(offsetof(T, tint) == 16);
    CHECK(offsetof(T, grid) == 32);
    CHECK(sizeof(T::grid[0][0]) == 16);  // float padded to the std140 stride
    CHECK(sizeof(T::grid[0]) == 48);     // 3 x 16
    CHECK(sizeof(T::grid) == 96);
    CHECK(sizeof(T) == 128);
}

TEST_CASE("scalar block: packed members - nested structs follow the SPIR-V offsets") {
    using T = fx::ScalarTraps;
    CHECK(offsetof(T, f) == 0);
    CHECK(offsetof(T, v3) == 4);         // vec3 needs only 4-byte alignment
    CHECK(offsetof(T, v3_array) == 16);  // vec3[2]: stride 12 -> 16..40
    CHECK(sizeof(T::v3_array) == 24);
    CHECK(sizeof(T::v3_array[0]) == 12);  // no padded element under scalar layout
    CHECK(offsetof(T, nested) == 40);     // struct aligned to 4 -> 40..68
    CHECK(sizeof(T::nested) == 28);       // not rounded up to 16 (or 32)
    CHECK(offsetof(T, m3) == 68);         // mat3: column stride 12 -> 36 bytes -> 104
    CHECK(sizeof(T::m3) == 36);
    CHECK(offsetof(T, u64) == 104);     // align 8
    CHECK(offsetof(T, inners) == 112);  // ScalarInner[2], stride 16 -> 144
    CHECK(offsetof(T, tail) == 144);
    CHECK(sizeof(T) == 152);  // 148, rounded to 8 by the uint64 member

    // ScalarNested { vec2 a; ScalarInner inner; float b; } and ScalarInner { float x; vec3 y; }
    CHECK(offsetof(fx::ScalarNested, a) == 0);
    CHECK(offsetof(fx::ScalarNested, inner) == 8);
    CHECK(offsetof(fx::ScalarNested, b) == 24);
    CHECK(offsetof(fx::ScalarInner, x) == 0);
    CHECK(offsetof(fx::ScalarInner, y) == 4);
    CHECK(sizeof(fx::ScalarInner) == 16);
}

TEST_CASE("runtime arrays: offset and stride constants - padded element types") {
    // ItemList { uint count; TrapItem items[]; }: items aligned to 16.
    CHECK(offsetof(fx::ItemList, count) == 0);
    CHECK(fx::ItemList::kItemsOffset == 16);
    CHECK(fx::ItemList::kItemsStride == 32);
    CHECK(sizeof(fx::ItemList) == 16);  // the part before the array: upload it, then the items
    static_assert(std::is_same_v<fx::ItemList::ItemsElement, fx::TrapItem>);
    // Vec3List { vec3 values[]; }: std430 vec3 array stride 16, element padded.
    CHECK(fx::Vec3List::kValuesOffset == 0);
    CHECK(fx::Vec3List::kValuesStride == 16);
    CHECK(sizeof(fx::Vec3List::ValuesElement) == 16);
    CHECK(fx::Echo::kValuesStride == 4);
    CHECK(fx::Counters::kCountersStride == 8);  // uint64_t[]
}

TEST_CASE("basic types: 4-byte aligned vectors - padded matrix columns") {
    CHECK(sizeof(fx::vec3) == 12);
    CHECK(alignof(fx::vec3) == 4);
    CHECK(sizeof(fx::mat3) == 48);
    CHECK(sizeof(fx::mat3_stride12) == 36);
    CHECK(sizeof(fx::mat2) == 16);
    CHECK(sizeof(fx::mat2_stride16) == 32);
    CHECK(sizeof(fx::mat3::columns[0]) == 16);  // vec3 column padded to the 16-byte stride
}

TEST_CASE("push constants: the struct is named after the block type") {
    static_assert(std::is_same_v<fx::roundtrip::Push, fx::RoundTripPush>);
    CHECK(fx::roundtrip::kPushConstantRange.offset == 0);
    CHECK(fx::roundtrip::kPushConstantRange.size == 8);
    CHECK(fx::roundtrip::kPushConstantRange.stageFlags == VK_SHADER_STAGE_COMPUTE_BIT);
}
