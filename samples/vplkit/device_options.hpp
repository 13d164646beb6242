#pragma once
// --device SEL and --validation, declared alike for every command that creates a Vulkan context.

#include "vplkit/context.hpp"

#include <CLI/CLI.hpp>

namespace vplkit::cli {

// --device (and, unless `validation` is false, --validation) into `options`.
void add_device_options(CLI::App& command, ContextOptions& options, bool validation = true);

}  // namespace vplkit::cli
