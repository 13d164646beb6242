#include "device_options.hpp"

namespace vplkit::cli {

void add_device_options(CLI::App& command, ContextOptions& options, bool validation) {
    command
        .add_option("--device", options.device,
                    "the device: auto, gpu, cpu (lavapipe), an index, or part of a name (default: the environment "
                    "variable VPLKIT_DEVICE, else auto)")
        ->option_text("SEL")
        ->check(CLI::Validator(
            [](std::string& text) { return text.empty() ? std::string("needs a non-empty value") : std::string(); }, "",
            "non-empty"));
    if (validation) command.add_flag("--validation", options.validation, "run with the Vulkan validation layer on");
}

}  // namespace vplkit::cli
