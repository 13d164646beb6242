#include "vplkit/stages/sort.hpp"

#include "vplkit/error.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/stages/bitonic_sort.hpp"
#include "vplkit/stages/radix_sort.hpp"

#include <string>
#include <utility>

namespace vplkit::stages {

namespace {

BitonicSortOptions bitonic_options(const SortOptions& options) {
    BitonicSortOptions bitonic;
    if (options.workgroup_size != 0) {
        bitonic.workgroup_size = options.workgroup_size;
    }
    return bitonic;
}

RadixSortOptions radix_options(const SortOptions& options) {
    RadixSortOptions radix;
    radix.key_bits = options.key_bits;
    if (options.workgroup_size != 0) {
        radix.workgroup_size = options.workgroup_size;
    }
    return radix;
}

void check_count(const char* algorithm, uint32_t count, uint32_t max_count) {
    if (count > max_count) {
        throw Error(std::string(algorithm) + " sort: " + std::to_string(count) +
                    " pairs, but the sorter was made for at most " + std::to_string(max_count));
    }
}

}  // namespace

const char* sort_algorithm_name(SortAlgorithm algorithm) {
    switch (algorithm) {
        case SortAlgorithm::bitonic:
            return "bitonic";
        case SortAlgorithm::radix:
            return "radix";
    }
    return "unknown";
}

std::optional<SortAlgorithm> parse_sort_algorithm(std::string_view name) {
    for (SortAlgorithm algorithm : {SortAlgorithm::bitonic, SortAlgorithm::radix}) {
        if (name == sort_algorithm_name(algorithm)) {
            return algorithm;
        }
    }
    return std::nullopt;
}

KeyValueSorter::KeyValueSorter(Device& device, uint32_t max_count, const SortOptions& options)
    : device_(&device), options_(options), max_count_(max_count) {
    if (options.key_bits < 1 || options.key_bits > 64) {
        throw Error("sort: key_bits " + std::to_string(options.key_bits) + " is outside 1..64");
    }
    if (max_count < 1) {
        throw Error("sort: max_count must be at least 1");
    }
    if (options.algorithm == SortAlgorithm::radix) {
        radix_ = std::make_unique<RadixSorter>(device, max_count, radix_options(options));
    }
}

KeyValueSorter::~KeyValueSorter() = default;
KeyValueSorter::KeyValueSorter(KeyValueSorter&&) noexcept = default;
KeyValueSorter& KeyValueSorter::operator=(KeyValueSorter&&) noexcept = default;

uint32_t KeyValueSorter::dispatch_count(uint32_t count) const {
    return radix_ ? radix_->dispatch_count(count) : bitonic_sort_dispatch_count(count, bitonic_options(options_));
}

void KeyValueSorter::record(VkCommandBuffer cmd, const BufferView& keys, const BufferView& values,
                            uint32_t count) const {
    if (radix_) {
        radix_->record(cmd, keys, values, count);
        return;
    }
    check_count("bitonic", count, max_count_);
    record_bitonic_sort(*device_, cmd, keys, values, count, bitonic_options(options_));
}

void KeyValueSorter::add_pass(StepList& passes, const BufferView& keys, const BufferView& values, uint32_t count,
                              std::string name) {
    if (radix_) {
        radix_->add_pass(passes, keys, values, count, std::move(name));
        return;
    }
    check_count("bitonic", count, max_count_);
    Device& device = *device_;
    const BitonicSortOptions bitonic = bitonic_options(options_);
    // add_bitonic_sort_pass checks the options and the count against the device, so that a bad
    // one is refused now rather than while the pass list records; but it names its pass "sort".
    // So it adds its pass to a list that is dropped, and the pass of the caller's name goes here.
    StepList check;
    add_bitonic_sort_pass(device, check, keys, values, count, bitonic);
    passes.add(std::move(name), {Use::read_write(keys), Use::read_write(values)},
               [&device, keys, values, count, bitonic](VkCommandBuffer cmd) {
                   record_bitonic_sort(device, cmd, keys, values, count, bitonic);
               });
}

}  // namespace vplkit::stages
