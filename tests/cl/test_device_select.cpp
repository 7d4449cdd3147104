// Device selection: an explicit selector, else WAVEPATH_DEVICE, else the
// first GPU or CPU; a selector that matches nothing names what exists.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "support/test_device.hpp"

using namespace wp;

namespace {

// Sets WAVEPATH_DEVICE for one scope and restores what was there before.
struct ScopedDeviceVariable {
    std::optional<std::string> saved;
    explicit ScopedDeviceVariable(const char* value) {
        if (const char* old = std::getenv("WAVEPATH_DEVICE"))
            saved = old;
        if (value)
            ::setenv("WAVEPATH_DEVICE", value, 1);
        else
            ::unsetenv("WAVEPATH_DEVICE");
    }
    ~ScopedDeviceVariable() {
        if (saved)
            ::setenv("WAVEPATH_DEVICE", saved->c_str(), 1);
        else
            ::unsetenv("WAVEPATH_DEVICE");
    }
};

} // namespace

TEST_CASE("device: an empty selector follows WAVEPATH_DEVICE, an explicit one ignores it") {
    const DeviceInfo wanted = test::device_info();
    {
        ScopedDeviceVariable variable(wanted.index_string().c_str());
        CHECK(select_device("").index_string() == wanted.index_string());
        CHECK(select_device(wanted.name).name == wanted.name);
    }
    {
        ScopedDeviceVariable variable("no-such-device");
        try {
            select_device("");
            FAIL("an unknown WAVEPATH_DEVICE was accepted");
        } catch (const DeviceError& e) {
            const std::string message = e.what();
            CHECK(message.find("'no-such-device' (from WAVEPATH_DEVICE)") != std::string::npos);
            CHECK(message.find(wanted.index_string()) != std::string::npos); // lists what exists
        }
        CHECK(select_device(wanted.index_string()).name == wanted.name);
    }
    {
        ScopedDeviceVariable variable("");
        CHECK_NOTHROW(select_device("")); // empty: the first GPU or CPU, as without it
    }
}

TEST_CASE("device: 'all' for a one-device command is that device where there is one") {
    ScopedDeviceVariable variable(nullptr);
    const std::vector<DeviceInfo> devices = list_devices();
    REQUIRE_FALSE(devices.empty());
    if (devices.size() == 1) {
        CHECK(select_device("all").index_string() == devices.front().index_string());
        CHECK(select_device(" ALL ").index_string() == devices.front().index_string());
    } else {
        // Not "names several" with one device: the count, and what exists.
        CHECK_THROWS_WITH(select_device("all"),
                          Catch::Contains("'all' names " + std::to_string(devices.size()) +
                                          " devices; available devices:"));
    }
    // A list is several selectors whatever the machine has.
    CHECK_THROWS_WITH(select_device("0:0,0:0"),
                      Catch::Contains("runs on one device, but the list '0:0,0:0' names several"));
}
