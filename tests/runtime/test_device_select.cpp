// Device choice: the ranking and the reason text on made-up device lists (no Vulkan needed),
// then the real thing on this machine's devices.

#include "vplkit/context.hpp"
#include "vplkit/device_info.hpp"
#include "vplkit/error.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

using vplkit::DeviceInfo;
using vplkit::DeviceType;

namespace {

DeviceInfo fake(uint32_t index, std::string name, DeviceType type, uint64_t memory = 0,
                std::vector<std::string> missing = {}) {
    DeviceInfo d;
    d.index = index;
    d.name = std::move(name);
    d.type = type;
    d.type_name = vplkit::device_type_name(type);
    d.driver_name = type == DeviceType::cpu ? "llvmpipe" : "vendor";
    d.device_local_memory_bytes = memory;
    d.missing = std::move(missing);
    return d;
}

const DeviceInfo kLavapipe = fake(0, "llvmpipe (LLVM 15.0.6, 256 bits)", DeviceType::cpu);
const DeviceInfo kIntegrated = fake(1, "Intel UHD 770", DeviceType::integrated_gpu, 1ull << 30);
const DeviceInfo kH100 = fake(2, "NVIDIA H100 80GB HBM3", DeviceType::discrete_gpu, 80ull << 30);

std::string error_of(const std::vector<DeviceInfo>& devices, const std::string& request) {
    try {
        vplkit::choose_device(devices, request, "VPLKIT_DEVICE");
    } catch (const vplkit::Error& e) {
        return e.what();
    }
    return "";
}

// Sets an environment variable for one scope and restores the previous value.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value) {
            setenv(name, value, 1);
        } else {
            unsetenv(name);
        }
    }
    ~ScopedEnv() {
        if (old_) {
            setenv(name_, old_->c_str(), 1);
        } else {
            unsetenv(name_);
        }
    }

private:
    const char* name_;
    std::optional<std::string> old_;
};

}  // namespace

TEST_CASE("auto choice ranks discrete over integrated over CPU and says why") {
    const auto choice = vplkit::choose_device({kLavapipe, kIntegrated, kH100}, "");
    CHECK(choice.index == 2);
    CHECK(choice.reason ==
          "picked NVIDIA H100 80GB HBM3 (discrete GPU) over Intel UHD 770 (integrated GPU), llvmpipe (LLVM 15.0.6, "
          "256 bits) (CPU)");
    CHECK(vplkit::choose_device({kLavapipe, kIntegrated}, "auto").index == 1);
}

TEST_CASE("auto choice falls back to lavapipe only without a GPU") {
    const auto choice = vplkit::choose_device({kLavapipe}, "");
    CHECK(choice.index == 0);
    CHECK(choice.reason == "no GPU found; using llvmpipe (LLVM 15.0.6, 256 bits) (CPU)");
}

TEST_CASE("auto choice skips a GPU that lacks a required feature and names it") {
    const DeviceInfo old_gpu = fake(1, "Old GPU", DeviceType::discrete_gpu, 8ull << 30, {"VK_KHR_push_descriptor"});
    const auto choice = vplkit::choose_device({kLavapipe, old_gpu}, "");
    CHECK(choice.index == 0);
    CHECK(choice.reason.find("no usable GPU") == 0);
    CHECK(choice.reason.find("skipped Old GPU (discrete GPU) lacks VK_KHR_push_descriptor") != std::string::npos);
}

TEST_CASE("between two discrete GPUs the one with more memory wins") {
    const DeviceInfo small = fake(0, "Small GPU", DeviceType::discrete_gpu, 8ull << 30);
    CHECK(vplkit::choose_device({small, kH100}, "").index == 2);
}

TEST_CASE("explicit requests: gpu - cpu - index - name part") {
    const std::vector<DeviceInfo> devices = {kLavapipe, kIntegrated, kH100};
    CHECK(vplkit::choose_device(devices, "gpu").index == 2);
    CHECK(vplkit::choose_device(devices, "cpu").index == 0);
    CHECK(vplkit::choose_device(devices, "lavapipe").index == 0);
    CHECK(vplkit::choose_device(devices, "1").index == 1);
    CHECK(vplkit::choose_device(devices, " h100 ").index == 2);
    const auto by_name = vplkit::choose_device(devices, "uhd", "--device");
    CHECK(by_name.index == 1);
    CHECK(by_name.reason == "picked Intel UHD 770 (integrated GPU) as requested by --device 'uhd'");
}

TEST_CASE("a request no device satisfies is a clear error listing the devices") {
    const std::vector<DeviceInfo> devices = {kLavapipe};
    const std::string missing = error_of(devices, "no-such-device");
    CHECK(missing.find("no Vulkan device matches 'no-such-device' (VPLKIT_DEVICE)") != std::string::npos);
    CHECK(missing.find("[0] llvmpipe (LLVM 15.0.6, 256 bits) (CPU)") != std::string::npos);
    CHECK(error_of(devices, "7").find("no Vulkan device with index 7") != std::string::npos);
    CHECK(error_of(devices, "gpu").find("no usable GPU") != std::string::npos);
    CHECK(error_of({}, "").find("no Vulkan device found") != std::string::npos);
}

TEST_CASE("requesting a device that lacks a required feature names the feature") {
    const DeviceInfo old_gpu =
        fake(0, "Old GPU", DeviceType::discrete_gpu, 0, {"Vulkan 1.3 (device has 1.2.0)", "shaderInt64"});
    const std::string message = error_of({old_gpu}, "0");
    CHECK(message.find("cannot run vplkit: it lacks Vulkan 1.3 (device has 1.2.0), shaderInt64") != std::string::npos);
}

TEST_CASE("this machine: automatic choice picks the best device and says why") {
    ScopedEnv no_override("VPLKIT_DEVICE", nullptr);
    const auto devices = vplkit::Context::enumerate_devices();
    REQUIRE(!devices.empty());
    bool gpu_usable = false;
    for (const auto& d : devices) {
        gpu_usable |= d.usable() && (d.type == DeviceType::discrete_gpu || d.type == DeviceType::integrated_gpu ||
                                     d.type == DeviceType::virtual_gpu);
    }
    auto context = vplkit::Context::create(vplkit::test::context_options(""));
    const DeviceInfo& info = context->info();
    MESSAGE("device: " << info.name << "; " << info.reason);
    if (gpu_usable) {
        CHECK(info.type != DeviceType::cpu);
        CHECK(info.reason.find("picked " + info.name) == 0);
    } else {
        // lavapipe here.
        CHECK(info.type == DeviceType::cpu);
        CHECK(info.reason == "no GPU found; using " + info.name + " (CPU)");
    }
}

TEST_CASE("this machine: 'cpu' gives lavapipe") {
    const auto devices = vplkit::Context::enumerate_devices();
    if (std::none_of(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.type == DeviceType::cpu; })) {
        MESSAGE("no CPU Vulkan device on this machine (mesa-vulkan-drivers not installed): nothing to check");
        return;
    }
    auto context = vplkit::Context::create(vplkit::test::context_options("cpu"));
    CHECK(context->info().type == DeviceType::cpu);
    CHECK(context->info().reason.find("as requested by device option 'cpu'") != std::string::npos);
}

TEST_CASE("this machine: VPLKIT_DEVICE applies when the program leaves the choice open") {
    ScopedEnv bogus("VPLKIT_DEVICE", "no-such-device");
    CHECK_THROWS_WITH_AS(vplkit::Context::create(vplkit::test::context_options("")),
                         doctest::Contains("no Vulkan device matches 'no-such-device' (VPLKIT_DEVICE)"), vplkit::Error);
    // An explicit option wins over the environment.
    auto context = vplkit::Context::create(vplkit::test::context_options(vplkit::test::test_device()));
    CHECK(context->info().usable());
}

TEST_CASE("this machine: a nonexistent device name is a clear error") {
    CHECK_THROWS_WITH_AS(vplkit::Context::create(vplkit::test::context_options("no-such-device")),
                         doctest::Contains("no Vulkan device matches 'no-such-device' (device option)"), vplkit::Error);
}
