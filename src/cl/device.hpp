// OpenCL platforms and devices: listing them and choosing one from a selector.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "cl/cl.hpp"

namespace wp {

// Thrown for a device selector that matches nothing; the message lists what exists.
class DeviceError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct DeviceInfo {
    int platform_index = 0;
    int device_index = 0; // within its platform
    cl::Device device;
    std::string platform_name;
    std::string name;
    std::string vendor;
    std::string type; // "GPU", "CPU", "accelerator", ...
    std::uint32_t compute_units = 0;
    std::uint64_t global_memory_bytes = 0;
    std::uint64_t local_memory_bytes = 0;
    std::size_t max_work_group_size = 0;
    std::string opencl_c_version;
    std::string driver_version;

    std::string index_string() const; // "platform:device", e.g. "0:1"
};

// Every device of every platform, in platform order. An ICD loader without
// platforms gives an empty list, not an error.
std::vector<DeviceInfo> list_devices();

// Picks a device: "P:D" is an index from list_devices(); anything else is a
// case-insensitive substring of the device name (first match). An empty
// selector means the environment variable WAVEPATH_DEVICE (same syntax) when
// it is set and not empty, else the first GPU, else the first CPU, else the
// first device.
// A selector that lists several devices (see select_devices) is refused:
// the commands that call this one run on one device. "all" is accepted on a
// machine with one device, and means that one.
DeviceInfo select_device(const std::string& selector);

// Picks the devices of one render: a comma-separated list of selectors as
// select_device takes them ("0:0,0:1", "gpu,cpu"), or "all" for every
// device. An index may appear once; a name takes the first matching device
// not already picked, so "pthread,pthread" picks two devices of that name.
// An empty selector means WAVEPATH_DEVICE (same syntax), else the default
// device of select_device. The result is in the list's order.
std::vector<DeviceInfo> select_devices(const std::string& selector);

// One line per device, as `wavepath devices` prints them.
std::string describe_devices(const std::vector<DeviceInfo>& devices);

} // namespace wp
