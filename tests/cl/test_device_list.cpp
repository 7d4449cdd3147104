// select_devices: the device list of a render ("0:0,0:1", names, "all").
// Lists of several distinct devices are tested where PoCL shows two
// (tests/app/test_cli_multi_device.cpp); here, what one device allows.
#include <catch2/catch.hpp>

#include <string>

#include "cl/device.hpp"
#include "support/test_device.hpp"

using namespace wp;

namespace {

std::string error_of(const std::string& selector) {
    try {
        select_devices(selector);
    } catch (const DeviceError& e) {
        return e.what();
    }
    return {};
}

} // namespace

TEST_CASE("device list: 'all' is every device in order, a single entry is that device") {
    const std::vector<DeviceInfo> every = list_devices();
    const std::vector<DeviceInfo> all = select_devices("all");
    REQUIRE(all.size() == every.size());
    for (std::size_t i = 0; i < all.size(); ++i)
        CHECK(all[i].index_string() == every[i].index_string());
    CHECK(select_devices(" ALL ").size() == every.size());

    const DeviceInfo wanted = test::device_info();
    const std::vector<DeviceInfo> one = select_devices(wanted.index_string());
    REQUIRE(one.size() == 1);
    CHECK(one[0].index_string() == wanted.index_string());
    const std::vector<DeviceInfo> by_name = select_devices(wanted.name);
    REQUIRE(by_name.size() == 1);
    CHECK(by_name[0].name == wanted.name);
}

TEST_CASE("device list: bad entries are named") {
    const std::string index = test::device_info().index_string();
    CHECK(error_of(index + ",7:7").find("no OpenCL device has index '7:7'") != std::string::npos);
    CHECK(error_of(index + ",nonexistent-gpu")
              .find("no OpenCL device name contains "
                    "'nonexistent-gpu'") != std::string::npos);
    CHECK(error_of(index + ",,").find("has an empty entry") != std::string::npos);
    CHECK(error_of(index + "," + index).find("device " + index) != std::string::npos);
    CHECK(error_of(index + "," + index).find("appears twice") != std::string::npos);
    CHECK(error_of(index + ",all").find("'all' in the device list") != std::string::npos);
    // A name matching only devices already picked says so (when one device
    // has that name; with two, the name would pick the second).
    const DeviceInfo wanted = test::device_info();
    int same_name = 0;
    for (const DeviceInfo& d : list_devices())
        same_name += d.name == wanted.name;
    if (same_name == 1)
        CHECK(error_of(index + "," + wanted.name).find("already in the list") != std::string::npos);
}

TEST_CASE("device list: a one-device command refuses a list") {
    const std::string index = test::device_info().index_string();
    // ("all" is that device on a one-device machine: test_device_select.cpp.)
    const std::string selector = index + "," + index;
    try {
        select_device(selector);
        FAIL("select_device accepted '" << selector << "'");
    } catch (const DeviceError& e) {
        CHECK(std::string(e.what()).find("runs on one device") != std::string::npos);
    }
}
