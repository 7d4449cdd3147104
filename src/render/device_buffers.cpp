#include "render/device_buffers.hpp"

#include <algorithm>
#include <string_view>

namespace wp {

namespace {

// A read-only buffer over `data` in place, which holds `owner` (the arrays
// `data` belongs to) until OpenCL deletes the buffer: the kernels may still
// read it after the caller lets go of both (commands queued hold buffers).
template <typename T>
cl::Buffer in_place_buffer(const cl::Context& context, const DeviceArray<T>& data,
                           const std::shared_ptr<const DeviceScene>& owner) {
    // A read-only buffer is never written through the pointer; the C API wants it non-const.
    cl::Buffer buffer(context, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, sizeof(T) * data.size(),
                      const_cast<T*>(data.data()));
    auto* held = new std::shared_ptr<const DeviceScene>(owner);
    try {
        buffer.setDestructorCallback(
            [](cl_mem, void* user_data) {
                delete static_cast<std::shared_ptr<const DeviceScene>*>(user_data);
            },
            held);
    } catch (...) {
        delete held;
        throw;
    }
    return buffer;
}

// Whether `name` is a row of WP_AOV_BUFFERS.
constexpr bool is_aov_row(std::string_view name) {
#define WP_IS_AOV(row, ...)                                                                        \
    if (name == #row)                                                                              \
        return true;
    WP_AOV_BUFFERS(WP_IS_AOV)
#undef WP_IS_AOV
    return false;
}

// The path buffers (WP_PATH_BUFFERS) into `b`, contents undefined.
void allocate_path_buffers(const cl::Context& context, std::uint64_t slots, std::uint64_t pixels,
                           bool aovs, DeviceBuffers& b) {
#define WP_ALLOCATE(name, type, per_slot, per_pixel, fixed)                                        \
    b.name = cl::Buffer(                                                                           \
        context, CL_MEM_READ_WRITE,                                                                \
        sizeof(type) *                                                                             \
            (!aovs && is_aov_row(#name)                                                            \
                 ? 1                                                                               \
                 : std::max<std::uint64_t>(1, (per_slot)*slots + (per_pixel)*pixels + (fixed))));
    WP_PATH_BUFFERS(WP_ALLOCATE)
#undef WP_ALLOCATE
}

} // namespace

PathBufferBytes path_buffer_bytes(bool aovs) {
    PathBufferBytes bytes;
#define WP_ADD_BYTES(name, type, slot_count, pixel_count, fixed_count)                             \
    if (!aovs && is_aov_row(#name)) {                                                              \
        bytes.fixed += sizeof(type); /* a one-element dummy */                                     \
    } else {                                                                                       \
        bytes.per_slot += sizeof(type) * (slot_count);                                             \
        bytes.per_pixel += sizeof(type) * (pixel_count);                                           \
        bytes.fixed += sizeof(type) * (fixed_count);                                               \
    }
    WP_PATH_BUFFERS(WP_ADD_BYTES)
#undef WP_ADD_BYTES
    return bytes;
}

std::uint64_t PathBufferBytes::largest(std::uint64_t slots, std::uint64_t pixels,
                                       const char** name) const {
    std::uint64_t most = 0;
    const char* most_name = "";
#define WP_LARGEST(buffer, type, per_slot, per_pixel, fixed)                                       \
    if (const std::uint64_t bytes =                                                                \
            sizeof(type) * ((per_slot)*slots + (per_pixel)*pixels + (fixed));                      \
        bytes > most) {                                                                            \
        most = bytes;                                                                              \
        most_name = #buffer;                                                                       \
    }
    WP_PATH_BUFFERS(WP_LARGEST)
#undef WP_LARGEST
    if (name)
        *name = most_name;
    return most;
}

bool shares_host_memory(const cl::Device& device, const void* data) {
    const auto alignment = device.getInfo<CL_DEVICE_MEM_BASE_ADDR_ALIGN>() / 8; // bits
    return device.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>() == CL_TRUE &&
           reinterpret_cast<std::uintptr_t>(data) % std::max<cl_uint>(alignment, 1) == 0;
}

DeviceBuffers allocate_device_buffers(const cl::Context& context, const DeviceScene& scene,
                                      std::uint64_t slots, std::uint64_t pixels, bool aovs) {
    DeviceBuffers b;
#define WP_UPLOAD(name, type) b.name = upload_buffer(context, scene.name);
    WP_SCENE_BUFFERS(WP_UPLOAD)
#undef WP_UPLOAD
    allocate_path_buffers(context, slots, pixels, aovs, b);
    return b;
}

DeviceBuffers allocate_device_buffers(const cl::Context& context, const cl::Device& device,
                                      const std::shared_ptr<const DeviceScene>& scene,
                                      std::uint64_t slots, std::uint64_t pixels, bool aovs) {
    DeviceBuffers b;
    // An empty array gets upload_buffer's dummy: OpenCL has no empty buffers.
#define WP_UPLOAD(name, type)                                                                      \
    b.name = !scene->name.empty() && shares_host_memory(device, scene->name.data())                \
                 ? in_place_buffer(context, scene->name, scene)                                    \
                 : upload_buffer(context, scene->name);
    WP_SCENE_BUFFERS(WP_UPLOAD)
#undef WP_UPLOAD
    allocate_path_buffers(context, slots, pixels, aovs, b);
    return b;
}

#define WP_BIND(name, ...) kernel.setArg(index++, buffers.name);

cl_uint bind_scene_buffers(cl::Kernel& kernel, cl_uint first, const DeviceBuffers& buffers) {
    cl_uint index = first;
    WP_SCENE_BUFFERS(WP_BIND)
    return index;
}

void bind_buffers(cl::Kernel& kernel, const DeviceBuffers& buffers) {
    cl_uint index = bind_scene_buffers(kernel, kLaunchArgument + 1, buffers);
    WP_PATH_BUFFERS(WP_BIND)
}

#undef WP_BIND

WpLaunch make_launch(std::uint32_t count, std::uint32_t ray_queue, bool from_finished,
                     bool sorted) {
    WpLaunch launch{};
    launch.count = count;
    launch.ray_queue = ray_queue;
    launch.from_finished = from_finished ? 1u : 0u;
    launch.sorted = sorted ? 1u : 0u;
    return launch;
}

} // namespace wp
