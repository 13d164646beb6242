#include "setting_flags.hpp"

namespace vplkit::cli {

namespace {

struct SettingFlag {
    std::string_view setting;  // a RenderSettings member path, or scene.lights
    std::string_view flag;     // what the command line calls it (a boolean's flag carries its value)
};

constexpr SettingFlag kSettingFlags[] = {
    {"scene.lights", "--sun or --point"},
    {"method", "--method"},
    {"vpl_source", "--vpl-source"},
    {"denoise", "--denoise"},
    {"direct_samples", "--direct-spp"},
    {"direct_sampler", "--direct"},
    {"glossy_branch", "--glossy-lobe"},
    {"force_all_stages", "--all-stages"},
    {"half_resolution_gi", "--gi-resolution half"},
    {"sst.nu_min", "--nu-min"},
    {"sst.sigma_max", "--sigma-max"},
    {"flc_levels", "--flc-levels"},
    {"flc_mu", "--flc-mu"},
    {"flc_vpls_per_point", "--flc-navg"},
    {"flc_subtiles", "--flc-subtiles"},
};

std::string_view flag_of(std::string_view setting) {
    for (const SettingFlag& s : kSettingFlags) {
        if (s.setting == setting) return s.flag;
    }
    return {};
}

}  // namespace

std::string with_flags(std::string_view message) {
    std::string out;
    size_t at = 0;
    while (at < message.size()) {
        const size_t open = message.find('`', at);
        const size_t close = open == std::string_view::npos ? open : message.find('`', open + 1);
        if (close == std::string_view::npos) break;
        const std::string_view flag = flag_of(message.substr(open + 1, close - open - 1));
        out += message.substr(at, open - at);
        out += flag.empty() ? message.substr(open, close + 1 - open) : flag;
        at = close + 1;
    }
    if (at < message.size()) out += message.substr(at);
    return out;
}

}  // namespace vplkit::cli
