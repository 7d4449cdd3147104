// The OpenCL device every test runs on, created once per test executable.
//
// Tests run on PoCL's CPU device unless WAVEPATH_TEST_DEVICE names another
// (same selector syntax as --device), so results do not depend on which GPU a
// developer happens to have.
//
// The context is never destroyed: OpenCL objects released from static
// destructors at exit outlive the driver's own thread-local and static state
// on some implementations (Oclgrind 21.10 writes to its freed API-call stack
// and corrupts the heap), so every static OpenCL object of the tests is
// allocated once and left to the process's end.
#pragma once

#include <cstdlib>
#include <string>

#include "cl/context.hpp"
#include "cl/device.hpp"

namespace wp::test {

// The device the tests run on: WAVEPATH_TEST_DEVICE, else PoCL's CPU device,
// else the default one.
inline DeviceInfo device_info() {
    if (const char* selector = std::getenv("WAVEPATH_TEST_DEVICE"))
        return select_device(selector);
    try {
        return select_device("pthread"); // PoCL's CPU device
    } catch (const DeviceError&) {
        return select_device("");
    }
}

inline DeviceContext& device() {
    static DeviceContext& context = *new DeviceContext(device_info());
    return context;
}

} // namespace wp::test
