// A cache file's name from its key text (cache_key.hpp).

#include "vplkit/cache_key.hpp"

#include <cstdint>
#include <cstdio>

namespace vplkit {

std::string fnv1a_hex(std::string_view text) {
    uint64_t h = 14695981039346656037ull;  // FNV-1a's 64-bit offset basis
    for (unsigned char c : text) {
        h ^= c;
        h *= 1099511628211ull;  // and its prime
    }
    char out[17];
    std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
    return out;
}

}  // namespace vplkit
