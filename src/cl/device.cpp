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

namespace {

// The selector the user meant: `requested`, else WAVEPATH_DEVICE; `from` says
// which, for messages.
std::string effective_selector(const std::string& requested, std::string& from) {
    from.clear();
    if (const char* variable = std::getenv("WAVEPATH_DEVICE"); requested.empty() && variable) {
        from = " (from WAVEPATH_DEVICE)";
        return variable;
    }
    return requested;
}

std::vector<DeviceInfo> available_devices() {
    std::vector<DeviceInfo> devices = list_devices();
    if (devices.empty())
        throw DeviceError("no OpenCL device found (is an ICD such as pocl-opencl-icd installed?)");
    return devices;
}

DeviceError no_match(const std::vector<DeviceInfo>& devices, const std::string& why) {
    std::ostringstream out;
    out << why << "; available devices:";
    for (const DeviceInfo& d : devices)
        out << " [" << d.index_string() << "] " << d.name << ";";
    std::string message = out.str();
    message.pop_back();
    return DeviceError(message);
}

const DeviceInfo& default_device(const std::vector<DeviceInfo>& devices) {
    for (const char* wanted : {"GPU", "CPU"})
        for (const DeviceInfo& d : devices)
            if (d.type == wanted)
                return d;
    return devices.front();
}

bool parse_index(const std::string& selector, int& platform, int& device) {
    char colon = 0, extra = 0;
    std::istringstream parse(selector);
    return (parse >> platform >> colon >> device) && colon == ':' && !(parse >> extra);
}

// The device one (non-empty) selector names, skipping those `taken` says
// are already picked when the selector is a name.
const DeviceInfo& match_device(const std::vector<DeviceInfo>& devices, const std::string& selector,
                               const std::string& from, const std::vector<bool>& taken) {
    int platform = -1, device = -1;
    if (parse_index(selector, platform, device)) {
        for (const DeviceInfo& d : devices)
            if (d.platform_index == platform && d.device_index == device)
                return d;
        throw no_match(devices, "no OpenCL device has index '" + selector + "'" + from);
    }
    const std::string needle = lowercase(selector);
    bool matched = false;
    for (std::size_t i = 0; i < devices.size(); ++i) {
        if (lowercase(devices[i].name).find(needle) == std::string::npos)
            continue;
        matched = true;
        if (!taken[i])
            return devices[i];
    }
    if (matched)
        throw no_match(devices, "every OpenCL device whose name contains '" + selector +
                                    "' is already in the list" + from);
    throw no_match(devices, "no OpenCL device name contains '" + selector + "'" + from);
}

std::vector<std::string> split_list(const std::string& text) {
    std::vector<std::string> items;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = text.find(',', start);
        items.push_back(trim(text.substr(start, comma - start)));
        if (comma == std::string::npos)
            return items;
        start = comma + 1;
    }
}

} // namespace

DeviceInfo select_device(const std::string& requested) {
    std::string from;
    const std::string selector = effective_selector(requested, from);
    if (selector.find(',') != std::string::npos)
        throw DeviceError("this command runs on one device, but the list '" + selector + "'" +
                          from + " names several");
    std::vector<DeviceInfo> devices = available_devices();
    // "all" is every device there is: on a machine with one, that one.
    if (lowercase(trim(selector)) == "all") {
        if (devices.size() == 1)
            return devices.front();
        throw no_match(devices, "this command runs on one device, but 'all'" + from + " names " +
                                    std::to_string(devices.size()) + " devices");
    }
    if (selector.empty())
        return default_device(devices);
    return match_device(devices, selector, from, std::vector<bool>(devices.size(), false));
}

std::vector<DeviceInfo> select_devices(const std::string& requested) {
    std::string from;
    const std::string selector = effective_selector(requested, from);
    std::vector<DeviceInfo> devices = available_devices();
    if (selector.empty())
        return {default_device(devices)};
    if (lowercase(trim(selector)) == "all")
        return devices;

    std::vector<bool> taken(devices.size(), false);
    std::vector<DeviceInfo> picked;
    for (const std::string& entry : split_list(selector)) {
        if (entry.empty())
            throw DeviceError("the device list '" + selector + "'" + from + " has an empty entry");
        if (lowercase(entry) == "all")
            throw DeviceError("'all' in the device list '" + selector + "'" + from +
                              " must stand alone");
        const DeviceInfo& device = match_device(devices, entry, from, taken);
        const auto position = static_cast<std::size_t>(&device - devices.data());
        if (taken[position])
            throw DeviceError("device " + device.index_string() + " (" + device.name +
                              ") appears twice in the device list '" + selector + "'" + from);
        taken[position] = true;
        picked.push_back(device);
    }
    return picked;
}

} // namespace wp
