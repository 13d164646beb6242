#include "vplkit/stages/glossy_lobe.hpp"

#include "vplkit/error.hpp"

#include <cmath>
#include <string>

namespace vplkit::stages {

void validate(const GlossyLobeOptions& options, const char* stage) {
    if (!(std::isfinite(options.max_roughness) && options.max_roughness >= 0.0f)) {
        throw Error(std::string(stage) + ": the glossy branch's max roughness must be a finite number >= 0, got " +
                    std::to_string(options.max_roughness));
    }
}

}  // namespace vplkit::stages
