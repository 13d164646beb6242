// Which device to run on, and a sentence saying why: the user should never have to guess
// whether a slow run was on lavapipe by accident.

#include "vplkit/device_info.hpp"
#include "vplkit/error.hpp"

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

namespace vplkit {
namespace {

int type_rank(DeviceType type) {
    switch (type) {
        case DeviceType::discrete_gpu:
            return 0;
        case DeviceType::integrated_gpu:
            return 1;
        case DeviceType::virtual_gpu:
            return 2;
        case DeviceType::cpu:
            return 3;
        case DeviceType::other:
            break;
    }
    return 4;
}

bool is_gpu(const DeviceInfo& d) {
    return type_rank(d.type) <= 2;
}

// lavapipe reports VK_PHYSICAL_DEVICE_TYPE_CPU; other CPU drivers (SwiftShader) too.
bool is_cpu(const DeviceInfo& d) {
    return d.type == DeviceType::cpu || d.driver_name == "llvmpipe";
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

std::string trim(const std::string& s) {
    const auto begin = s.find_first_not_of(" \t\r\n");
    if (begin == std::string::npos) return "";
    const auto end = s.find_last_not_of(" \t\r\n");
    return s.substr(begin, end - begin + 1);
}

std::string label(const DeviceInfo& d) {
    return d.name + " (" + d.type_name + ")";
}

std::string join(const std::vector<std::string>& parts, const char* separator) {
    std::string out;
    for (size_t i = 0; i < parts.size(); ++i) {
        if (i) out += separator;
        out += parts[i];
    }
    return out;
}

std::string missing_text(const DeviceInfo& d) {
    return "lacks " + join(d.missing, ", ");
}

std::string device_list(const std::vector<DeviceInfo>& devices) {
    std::vector<std::string> lines;
    for (const auto& d : devices) {
        lines.push_back("[" + std::to_string(d.index) + "] " + label(d) + (d.usable() ? "" : ", " + missing_text(d)));
    }
    return join(lines, "; ");
}

// Better first: type, then the most device-local memory (the bigger of two discrete GPUs),
// then enumeration order so the choice is stable.
bool better(const DeviceInfo& a, const DeviceInfo& b) {
    if (type_rank(a.type) != type_rank(b.type)) return type_rank(a.type) < type_rank(b.type);
    if (a.device_local_memory_bytes != b.device_local_memory_bytes)
        return a.device_local_memory_bytes > b.device_local_memory_bytes;
    return a.index < b.index;
}

const DeviceInfo* best_of(const std::vector<const DeviceInfo*>& candidates) {
    const DeviceInfo* best = nullptr;
    for (const DeviceInfo* d : candidates) {
        if (!best || better(*d, *best)) best = d;
    }
    return best;
}

DeviceChoice require_usable(const DeviceInfo& d, const std::string& why, const std::string& request,
                            const std::string& source) {
    if (!d.usable()) {
        throw Error("vplkit: device [" + std::to_string(d.index) + "] " + label(d) + ", requested by " + source + " '" +
                    request + "', cannot run vplkit: it " + missing_text(d));
    }
    return {d.index, why};
}

}  // namespace

DeviceChoice choose_device(const std::vector<DeviceInfo>& devices, const std::string& raw_request,
                           const std::string& source) {
    if (devices.empty()) {
        throw Error(
            "vplkit: no Vulkan device found; install a Vulkan driver (on Debian 12, 'mesa-vulkan-drivers' "
            "provides lavapipe, a CPU device)");
    }
    const std::string request = trim(raw_request);
    const std::string key = lower(request);
    const std::string requested = " as requested by " + source + " '" + request + "'";

    if (key.empty() || key == "auto") {
        std::vector<const DeviceInfo*> usable;
        std::vector<std::string> skipped;
        for (const auto& d : devices) {
            if (d.usable()) {
                usable.push_back(&d);
            } else {
                skipped.push_back(label(d) + " " + missing_text(d));
            }
        }
        if (usable.empty()) throw Error("vplkit: no Vulkan device can run vplkit: " + device_list(devices));
        const DeviceInfo& best = *best_of(usable);
        std::vector<const DeviceInfo*> ranked = usable;
        std::sort(ranked.begin(), ranked.end(),
                  [](const DeviceInfo* a, const DeviceInfo* b) { return better(*a, *b); });
        std::vector<std::string> others;
        for (const DeviceInfo* d : ranked) {
            if (d != &best) others.push_back(label(*d));
        }
        std::string reason;
        if (is_gpu(best)) {
            reason = "picked " + label(best) +
                     (others.empty() ? " (the only usable device)" : " over " + join(others, ", "));
        } else {
            const bool gpu_present = std::any_of(devices.begin(), devices.end(), is_gpu);
            reason = std::string(gpu_present ? "no usable GPU" : "no GPU found") + "; using " + label(best);
        }
        if (!skipped.empty()) reason += "; skipped " + join(skipped, "; ");
        return {best.index, reason};
    }

    if (key == "gpu") {
        std::vector<const DeviceInfo*> gpus;
        for (const auto& d : devices) {
            if (is_gpu(d) && d.usable()) gpus.push_back(&d);
        }
        if (gpus.empty()) {
            throw Error("vplkit: no usable GPU" + requested + " (devices: " + device_list(devices) +
                        "); use 'cpu' to run on lavapipe");
        }
        const DeviceInfo& best = *best_of(gpus);
        return {best.index, "picked " + label(best) + requested};
    }

    if (key == "cpu" || key == "lavapipe" || key == "llvmpipe") {
        std::vector<const DeviceInfo*> cpus;
        for (const auto& d : devices) {
            if (is_cpu(d)) cpus.push_back(&d);
        }
        if (cpus.empty()) {
            throw Error("vplkit: no CPU Vulkan device" + requested + " (devices: " + device_list(devices) +
                        "); on Debian 12 install 'mesa-vulkan-drivers' for lavapipe");
        }
        const DeviceInfo& d = *best_of(cpus);
        return require_usable(d, "picked " + label(d) + requested, request, source);
    }

    if (std::all_of(key.begin(), key.end(), [](unsigned char c) { return std::isdigit(c); })) {
        const unsigned long index = key.size() > 9 ? devices.size() : std::stoul(key);
        if (index >= devices.size()) {
            throw Error("vplkit: no Vulkan device with index " + request + " (" + source +
                        "); devices: " + device_list(devices));
        }
        const DeviceInfo& d = devices[index];
        return require_usable(d, "picked " + label(d) + requested, request, source);
    }

    std::vector<const DeviceInfo*> matches;
    for (const auto& d : devices) {
        if (lower(d.name).find(key) != std::string::npos) matches.push_back(&d);
    }
    if (matches.empty()) {
        throw Error("vplkit: no Vulkan device matches '" + request + "' (" + source +
                    "); expected auto, gpu, cpu, an index or part of a name; devices: " + device_list(devices));
    }
    const DeviceInfo& d = *best_of(matches);
    std::string why = "picked " + label(d) + requested;
    if (matches.size() > 1) why += " (best of " + std::to_string(matches.size()) + " matching devices)";
    return require_usable(d, why, request, source);
}

}  // namespace vplkit
