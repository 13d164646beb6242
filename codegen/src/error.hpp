// The one error type of vplkit-codegen. Every failure (bad input, unsupported shader
// construct, conflicting layouts) is reported as a single line on stderr by main(),
// before any file is written.
#pragma once

#include <stdexcept>
#include <string>

namespace vplkit::codegen {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace vplkit::codegen
