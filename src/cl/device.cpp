#include "cl/device.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>

namespace wp {
namespace {

std::string trim(std::string s) {
    // Drivers pad names with spaces and NULs.
    while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back()))))
        s.pop_back();
    std::size_t start = 0;
    while (start < s.size() && std::isspace(static_cast<unsigned char>(s[start])))
        ++start;
    return s.substr(start);
}

std::string lowercase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string type_name(cl_device_type type) {
    if (type & CL_DEVICE_TYPE_GPU)
        return "GPU";
    if (type & CL_DEVICE_TYPE_CPU)
        return "CPU";
    if (type & CL_DEVICE_TYPE_ACCELERATOR)
        return "accelerator";
    return "other";
}

std::string mebibytes(std::uint64_t bytes) {
    std::ostringstream out;
    if (bytes >= (1ull << 30))
        out << static_cast<double>(bytes >> 20) / 1024.0 << " GiB";
    else if (bytes >= (1ull << 20))
        out << (bytes >> 20) << " MiB";
    else
        out << (bytes >> 10) << " KiB";
    return out.str();
}

} // namespace

std::string DeviceInfo::index_string() const {
    return std::to_string(platform_index) + ":" + std::to_string(device_index);
}

std::vector<DeviceInfo> list_devices() {
    std::vector<cl::Platform> platforms;
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error&) {
        return {}; // CL_PLATFORM_NOT_FOUND_KHR: no ICD installed
    }
    std::vector<DeviceInfo> result;
    for (std::size_t p = 0; p < platforms.size(); ++p) {
        std::vector<cl::Device> devices;
        try {
            platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
        } catch (const cl::Error&) {
            continue; // a platform with no devices
        }
        for (std::size_t d = 0; d < devices.size(); ++d) {
            const cl::Device& device = devices[d];
            DeviceInfo info;
            info.platform_index = static_cast<int>(p);
            info.device_index = static_cast<int>(d);
            info.device = device;
            info.platform_name = trim(platforms[p].getInfo<CL_PLATFORM_NAME>());
            info.name = trim(device.getInfo<CL_DEVICE_NAME>());
            info.vendor = trim(device.getInfo<CL_DEVICE_VENDOR>());
            info.type = type_name(device.getInfo<CL_DEVICE_TYPE>());
            info.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
            info.global_memory_bytes = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
            info.local_memory_bytes = device.getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
            info.max_work_group_size = device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
            info.opencl_c_version = trim(device.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
            info.driver_version = trim(device.getInfo<CL_DRIVER_VERSION>());
            result.push_back(std::move(info));
        }
    }
    return result;
}

std::string describe_devices(const std::vector<DeviceInfo>& devices) {
    std::ostringstream out;
    for (const DeviceInfo& d : devices) {
        out << d.index_string() << "  " << d.name << "\n"
            << "       platform: " << d.platform_name << ", vendor: " << d.vendor
            << ", type: " << d.type << "\n"
            << "       compute units: " << d.compute_units
            << ", global memory: " << mebibytes(d.global_memory_bytes)
            << ", local memory: " << mebibytes(d.local_memory_bytes)
            << ", max work-group size: " << d.max_work_group_size << "\n"
            << "       " << d.opencl_c_version << ", driver " << d.driver_version << "\n";
    }
    return out.str();
}

DeviceInfo select_device(const std::string& requested) {
    std::string selector = requested, from;
    if (const char* variable = std::getenv("WAVEPATH_DEVICE"); selector.empty() && variable) {
        selector = variable;
        from = " (from WAVEPATH_DEVICE)";
    }
    std::vector<DeviceInfo> devices = list_devices();
    if (devices.empty())
        throw DeviceError("no OpenCL device found (is an ICD such as pocl-opencl-icd installed?)");

    auto fail = [&](const std::string& why) -> DeviceError {
        std::ostringstream out;
        out << why << "; available devices:";
        for (const DeviceInfo& d : devices)
            out << " [" << d.index_string() << "] " << d.name << ";";
        std::string message = out.str();
        message.pop_back();
        return DeviceError(message);
    };

    if (selector.empty()) {
        for (const char* wanted : {"GPU", "CPU"})
            for (const DeviceInfo& d : devices)
                if (d.type == wanted)
                    return d;
        return devices.front();
    }

    int platform = -1, device = -1;
    char colon = 0, extra = 0;
    std::istringstream parse(selector);
    if ((parse >> platform >> colon >> device) && colon == ':' && !(parse >> extra)) {
        for (const DeviceInfo& d : devices)
            if (d.platform_index == platform && d.device_index == device)
                return d;
        throw fail("no OpenCL device has index '" + selector + "'" + from);
    }

    std::string needle = lowercase(selector);
    for (const DeviceInfo& d : devices)
        if (lowercase(d.name).find(needle) != std::string::npos)
            return d;
    throw fail("no OpenCL device name contains '" + selector + "'" + from);
}

} // namespace wp
