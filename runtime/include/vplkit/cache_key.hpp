#pragma once
// A cache file's name from its key text (the budget's calibration, bench gi's ground truth):
// FNV-1a, 64 bits, as 16 hex digits. Stable across runs and builds; a collision is harmless
// where the caller stores the key beside the data and compares it on reading.

#include <string>
#include <string_view>

namespace vplkit {

std::string fnv1a_hex(std::string_view text);

}  // namespace vplkit
