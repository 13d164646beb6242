// `vplkit info`: what Vulkan sees, which device vplkit would run on and why, and what that
// device offers of the features vplkit uses. The first thing to run on a new machine.

#include "cli.hpp"
#include "commands.hpp"
#include "device_options.hpp"

#include "vplkit/context.hpp"
#include "vplkit/device_info.hpp"

#include <cstdio>
#include <memory>
#include <string>

namespace vplkit::cli {

namespace {

const char* yes_no(bool b) {
    return b ? "yes" : "no";
}

void feature(const char* name, bool present, const std::string& detail = {}) {
    std::printf("  %-28s %s%s\n", name, yes_no(present), detail.empty() ? "" : (" (" + detail + ")").c_str());
}

std::string gib(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1ull << 30));
    return text;
}

int run_info(const ContextOptions& options) {
    const auto devices = Context::enumerate_devices();
    std::printf("Vulkan devices: %zu\n", devices.size());
    for (const DeviceInfo& d : devices) {
        std::printf("  [%u] %s\n      %s, driver %s (%s), Vulkan %s\n", d.index, d.name.c_str(), d.type_name.c_str(),
                    d.driver_name.empty() ? "?" : d.driver_name.c_str(), d.driver_info.c_str(),
                    d.api_version_string.c_str());
        if (!d.usable()) {
            std::string missing;
            for (const auto& m : d.missing) missing += (missing.empty() ? "" : ", ") + m;
            std::printf("      cannot run vplkit: lacks %s\n", missing.c_str());
        }
    }

    std::unique_ptr<Context> context;
    try {
        context = Context::create(options);
    } catch (...) {
        std::printf("\nno device chosen\n");
        std::fflush(stdout);
        throw;
    }
    const DeviceInfo& info = context->info();
    const DeviceFeatures& f = info.features;
    std::printf("\nchosen: [%u] %s\n  why: %s\n\n", info.index, info.name.c_str(), info.reason.c_str());
    std::printf("  %-28s %u (min %u, max %u)\n", "subgroup size", info.subgroup_size, info.min_subgroup_size,
                info.max_subgroup_size);
    std::printf("  %-28s %s\n", "subgroup ops", subgroup_operations_string(info.subgroup_operations).c_str());
    std::printf("  %-28s %s, %g ns per tick, %u valid bits\n", "timestamps", yes_no(f.timestamps),
                double(info.timestamp_period_ns), info.timestamp_valid_bits);
    std::printf("  %-28s %u bytes\n", "shared memory per workgroup", info.max_shared_memory_bytes);
    std::printf("  %-28s %u x %u x %u, %u invocations\n", "max workgroup size", info.max_workgroup_size[0],
                info.max_workgroup_size[1], info.max_workgroup_size[2], info.max_workgroup_invocations);
    std::printf("  %-28s %u\n", "max push descriptors", info.max_push_descriptors);
    std::printf("  %-28s %s\n", "device-local memory", gib(info.device_local_memory_bytes).c_str());

    std::printf("\nrequired features:\n");
    feature("Vulkan 1.3", f.vulkan_1_3, info.api_version_string);
    feature("push descriptors", f.push_descriptor, "VK_KHR_push_descriptor");
    feature("synchronization2", f.synchronization2);
    feature("shaderInt64", f.shader_int64);
    feature("scalar block layout", f.scalar_block_layout);
    feature("timestamps", f.timestamps);
    std::printf("optional features (enabled when present):\n");
    feature("int64 buffer atomics", f.shader_buffer_int64_atomics, "shaderBufferInt64Atomics");
    feature("float atomic add (buffer)", f.shader_buffer_float32_atomic_add, "VK_EXT_shader_atomic_float");
    feature("float atomic add (shared)", f.shader_shared_float32_atomic_add, "VK_EXT_shader_atomic_float");
    feature("shaderFloat64", f.shader_float64);
    feature("subgroup ops in compute", f.subgroup_basic, subgroup_operations_string(info.subgroup_operations));
    feature("subgroup size control", f.subgroup_size_control && f.compute_full_subgroups,
            "subgroupSizeControl + computeFullSubgroups");
    std::printf("reported only:\n");
    feature("ray tracing pipeline", f.ray_tracing_pipeline && f.acceleration_structure,
            "VK_KHR_ray_tracing_pipeline + VK_KHR_acceleration_structure");
    feature("ray query", f.ray_query && f.acceleration_structure, "VK_KHR_ray_query");

    if (options.validation) {
        std::printf("\nvalidation layer on: %llu message(s)\n",
                    (unsigned long long)context->validation_message_count());
        return context->validation_message_count() == 0 ? 0 : 1;
    }
    return 0;
}

}  // namespace

void add_info(CLI::App& vplkit, Runners& runners) {
    CLI::App* info = add_command(
        vplkit, "info", "list the Vulkan devices, the one vplkit picks and why, and its features",
        "Lists every Vulkan device, creates a context on the one vplkit picks (or --device) and prints why it was "
        "picked, its limits and which of the features vplkit uses it has.");
    auto options = std::make_shared<ContextOptions>();
    add_device_options(*info, *options);
    runners.push_back({info, [options] { return run_info(*options); }});
}

}  // namespace vplkit::cli
