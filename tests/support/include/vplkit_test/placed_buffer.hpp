#pragma once
// A view onto records placed among decoys: the tests of the addressed paths (past
// maxStorageBufferRange) check that a stage reads exactly its view, at an unaligned offset.

#include "vplkit/buffer.hpp"
#include "vplkit_test/context.hpp"

#include <vector>

namespace vplkit::test {

constexpr VkBufferUsageFlags kAddressedUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

// `records` after `before` decoys and followed by `after` more, in one device buffer kept in
// `keep`; the view covers `records` only. A stage that read past the view's start or end would
// meet decoys.
template <class T>
BufferView placed(std::vector<Buffer>& keep, const std::vector<T>& records, const T& decoy, size_t before, size_t after,
                  const char* name) {
    std::vector<T> contents(before, decoy);
    contents.insert(contents.end(), records.begin(), records.end());
    contents.insert(contents.end(), after, decoy);
    keep.push_back(Buffer::create(context(), contents.size() * sizeof(T), kAddressedUsage, MemoryUse::device, name));
    keep.back().upload(contents);
    return {keep.back().handle(), before * sizeof(T), records.size() * sizeof(T), name};
}

}  // namespace vplkit::test
