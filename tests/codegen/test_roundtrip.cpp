// Round trip on lavapipe through the generated headers: roundtrip.comp writes base + counter
// into every component of every trap struct (and echoes the std140 block the host filled);
// the host reads the buffers back through the generated structs and checks every field, in
// the order the shader wrote them. It also exercises the generated Pipeline: create() with a
// non-default Spec (workgroup size 4 via local_size_x_id, an offset constant) and dispatch()
// with push descriptors, push constants and a thread count that is not a multiple of 4.
#include <doctest/doctest.h>

#include <cstring>
#include <string>
#include <vector>

#include "vk_test_device.hpp"
#include "vplkit/fixtures/roundtrip.hpp"

namespace fx = vplkit::fixtures;
namespace rt = vplkit::fixtures::roundtrip;
using vplkit::codegen_test::HostBuffer;
using vplkit::codegen_test::TestDevice;

namespace {

// The host side of the shader's next_*() functions.
struct Sequence {
    uint32_t next;
    uint32_t u() { return next++; }
    float f() { return float(next++); }
    uint64_t u64() {
        const uint64_t v = next++;
        return (v << 32) | v;
    }
    int64_t i64() { return -(int64_t(next++) << 12); }
};

void check(const fx::vec2& v, Sequence& s) {
    CHECK(v.x == s.f());
    CHECK(v.y == s.f());
}
void check(const fx::vec3& v, Sequence& s) {
    CHECK(v.x == s.f());
    CHECK(v.y == s.f());
    CHECK(v.z == s.f());
}
void check(const fx::vec4& v, Sequence& s) {
    CHECK(v.x == s.f());
    CHECK(v.y == s.f());
    CHECK(v.z == s.f());
    CHECK(v.w == s.f());
}
template <typename T, std::size_t Stride>
void check(const fx::padded<T, Stride>& p, Sequence& s) {
    check(p.value, s);
}
template <typename Matrix>
void check_matrix(const Matrix& m, Sequence& s) {
    for (const auto& column : m.columns) check(column, s);
}

void check_untouched(const uint8_t* bytes, std::size_t size, const char* what) {
    for (std::size_t i = 0; i < size; ++i) {
        INFO(what << " byte " << i);
        CHECK(bytes[i] == 0xCD);
    }
}

fx::vec2 vec2_of(Sequence& s) {
    return {s.f(), s.f()};
}
fx::vec3 vec3_of(Sequence& s) {
    return {s.f(), s.f(), s.f()};
}

// Fills the std140 block through the generated struct, in the order the shader echoes it.
fx::Std140Traps make_std140(Sequence s) {
    fx::Std140Traps t;
    std::memset(&t, 0xCD, sizeof(t));
    for (auto& e : t.v2_array) e.value = vec2_of(s);
    for (auto& e : t.f_array) e.value = s.f();
    t.v3 = vec3_of(s);
    t.after_v3 = s.f();
    for (auto& c : t.m3.columns) c.value = vec3_of(s);
    for (auto& c : t.m2.columns) c.value = vec2_of(s);
    for (auto& c : t.m2x3.columns) c.value = vec3_of(s);
    for (auto& c : t.m3x2.columns) c.value = vec2_of(s);
    t.inner.direction = vec3_of(s);
    t.inner.weight = s.f();
    t.after_inner = s.f();
    t.u2 = {s.u(), s.u()};
    return t;
}

template <typename T>
T read(const HostBuffer& b, std::size_t offset = 0) {
    T value;
    std::memcpy(&value, static_cast<const uint8_t*>(b.mapped) + offset, sizeof(T));
    return value;
}

}  // namespace

TEST_CASE("round trip on lavapipe: every trap field - generated Pipeline create and dispatch") {
    TestDevice device;

    rt::Spec spec;
    spec.kGroupSize = 4;  // also the workgroup size (local_size_x_id = 0)
    spec.kOffset = 1000;
    rt::Pipeline pipeline;
    REQUIRE(rt::Pipeline::create(device.device(), VK_NULL_HANDLE, spec, &pipeline) == VK_SUCCESS);
    CHECK(pipeline.workgroup_size == std::array<uint32_t, 3>{4, 1, 1});

    constexpr uint32_t kItems = 10;  // 3 groups of 4: the last group is partly idle
    constexpr uint32_t kEchoCount = 64;
    HostBuffer std430 = device.create_buffer(sizeof(fx::Std430Traps));
    HostBuffer std140 = device.create_buffer(sizeof(fx::Std140Traps));
    HostBuffer scalar = device.create_buffer(sizeof(fx::ScalarTraps));
    HostBuffer items = device.create_buffer(fx::ItemList::kItemsOffset + fx::ItemList::kItemsStride * kItems);
    HostBuffer vec3s = device.create_buffer(fx::Vec3List::kValuesStride * kItems);
    HostBuffer echo = device.create_buffer(fx::Echo::kValuesStride * kEchoCount);
    for (HostBuffer* b : {&std430, &scalar, &items, &vec3s, &echo}) std::memset(b->mapped, 0xCD, b->size);

    const uint32_t std140_base = 5000;
    const fx::Std140Traps std140_in = make_std140(Sequence{std140_base});
    std::memcpy(std140.mapped, &std140_in, sizeof(std140_in));

    rt::Bindings bindings;
    bindings.std430_traps = std430.whole();
    bindings.std140_traps = std140.whole();
    bindings.scalar_traps = scalar.whole();
    bindings.item_list = items.whole();
    bindings.vec3_list = vec3s.whole();
    bindings.echo = echo.whole();
    rt::Push push{};
    push.base = 7;
    push.item_count = kItems;
    device.run([&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, bindings, push, kItems); });

    const uint32_t base = push.base + spec.kOffset;

    {
        INFO("std430 block");
        const auto t = read<fx::Std430Traps>(std430);
        Sequence s{base};
        check(t.v3, s);
        CHECK(t.after_v3 == s.f());
        for (const auto& e : t.v3_array) check(e, s);
        for (const auto& e : t.v2_array) check(e, s);
        for (float e : t.f_array) CHECK(e == s.f());
        check_matrix(t.m3, s);
        check_matrix(t.m4, s);
        check_matrix(t.m2x3, s);
        check_matrix(t.m3x2, s);
        check_matrix(t.m2, s);
        CHECK(t.u64 == s.u64());
        CHECK(t.i64 == s.i64());
        CHECK(t.u64v2.x == s.u64());
        CHECK(t.u64v2.y == s.u64());
        CHECK(t.flag == 1u);
        check(t.inner.direction, s);
        CHECK(t.inner.weight == s.f());
        for (const auto& item : t.items) {
            check(item.position, s);
            CHECK(item.radius == s.f());
            check(item.normal, s);
            check_untouched(item._pad0, sizeof(item._pad0), "TrapItem::_pad0");
        }
        CHECK(t.tail == s.f());
        // Nothing landed in the padding: every field is where the shader put it.
        check_untouched(t._pad0, sizeof(t._pad0), "Std430Traps::_pad0");
        check_untouched(t._pad1, sizeof(t._pad1), "Std430Traps::_pad1");
        check_untouched(t._pad2, sizeof(t._pad2), "Std430Traps::_pad2");
    }

    {
        INFO("scalar block");
        const auto t = read<fx::ScalarTraps>(scalar);
        // The shader writes std430 first, then scalar: continue the sequence after std430's
        // 3+1+9+6+3+9+16+6+6+4 floats, 4 64-bit values, 3+1 inner and 2*7 items, and the tail.
        Sequence s{base + 3 + 1 + 9 + 6 + 3 + 9 + 16 + 6 + 6 + 4 + 4 + 4 + 14 + 1};
        CHECK(t.f == s.f());
        check(t.v3, s);
        for (const auto& e : t.v3_array) check(e, s);
        check(t.nested.a, s);
        CHECK(t.nested.inner.x == s.f());
        check(t.nested.inner.y, s);
        CHECK(t.nested.b == s.f());
        check_matrix(t.m3, s);
        CHECK(t.u64 == s.u64());
        for (const auto& e : t.inners) {
            CHECK(e.x == s.f());
            check(e.y, s);
        }
        CHECK(t.tail == s.f());
    }

    {
        INFO("std140 block, echoed component by component");
        Sequence s{std140_base};
        constexpr uint32_t kStd140Values = 6 + 2 + 3 + 1 + 9 + 4 + 6 + 6 + 4 + 1 + 2;
        for (uint32_t k = 0; k < kStd140Values; ++k) {
            INFO("echo value " << k);
            CHECK(read<float>(echo, k * fx::Echo::kValuesStride) == float(s.u()));
        }
        CHECK(read<uint32_t>(echo, kStd140Values * fx::Echo::kValuesStride) == 0xCDCDCDCDu);  // nothing beyond
    }

    {
        INFO("runtime arrays: every thread of the partial last group");
        CHECK(read<fx::ItemList>(items).count == kItems);
        for (uint32_t i = 0; i < kItems; ++i) {
            INFO("item " << i);
            Sequence s{base + 10000 + i * 16};
            const auto item =
                read<fx::ItemList::ItemsElement>(items, fx::ItemList::kItemsOffset + i * fx::ItemList::kItemsStride);
            check(item.position, s);
            CHECK(item.radius == s.f());
            check(item.normal, s);
            check(read<fx::Vec3List::ValuesElement>(vec3s, i * fx::Vec3List::kValuesStride), s);
        }
    }

    for (HostBuffer* b : {&std430, &std140, &scalar, &items, &vec3s, &echo}) device.destroy(*b);
    pipeline.destroy();
    CHECK(pipeline.pipeline == VK_NULL_HANDLE);

    std::string messages;
    for (const std::string& m : device.validation_messages()) messages += m + "\n";
    INFO("validation messages:\n" << messages);
    CHECK(device.validation_messages().empty());
}
