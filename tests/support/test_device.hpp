// The OpenCL device every test runs on, created once per test executable.
//
// Tests run on PoCL's CPU device unless WAVEPATH_TEST_DEVICE names another
// (same selector syntax as --device), so results do not depend on which GPU a
// developer happens to have.
#pragma once

#include <cstdlib>
#include <string>

#include "cl/context.hpp"
#include "cl/device.hpp"

namespace wp::test {

inline DeviceContext& device() {
    static DeviceContext context([] {
        if (const char* selector = std::getenv("WAVEPATH_TEST_DEVICE"))
            return select_device(selector);
        try {
            return select_device("pthread"); // PoCL's CPU device
        } catch (const DeviceError&) {
            return select_device("");
        }
    }());
    return context;
}

} // namespace wp::test
