#pragma once
// The runtime names settings in its own terms, "`vpl_source` ir" (render_settings.hpp); the
// command line shows its flags instead, "--vpl-source ir". One table maps the one to the other.

#include <string>
#include <string_view>

namespace vplkit::cli {

// `message` with every backquoted setting the table knows replaced by its flag; others are left as
// they are (still the runtime's name, so still findable).
std::string with_flags(std::string_view message);

}  // namespace vplkit::cli
