#pragma once
// The budget model on disk: a text file, its first lines the format and the key it was measured
// for, then the stages' coefficients and the noise measurements, a line each. Written to a
// temporary name and renamed, so a failure leaves no partial file.

#include "vplkit/budget_calibration.hpp"

#include <filesystem>
#include <optional>
#include <string>

namespace vplkit::detail {

// The file's name for `key`: a hash of it, so any scene name or path makes a plain file name.
std::filesystem::path budget_cache_file(const std::filesystem::path& dir, const std::string& key);

// The model in `file` when it exists, is of this format and was written for `key`; else nothing
// (a stale or foreign file is recalibrated over, not an error).
std::optional<BudgetModel> read_budget_cache(const std::filesystem::path& file, const std::string& key);

// Throws vplkit::Error naming the file when it cannot be written.
void write_budget_cache(const std::filesystem::path& file, const std::string& key, const BudgetModel& model);

}  // namespace vplkit::detail
