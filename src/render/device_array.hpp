// The host arrays of a flattened scene, aligned so that a device may use
// them in place.
//
// A device that shares the host's memory (CL_DEVICE_HOST_UNIFIED_MEMORY:
// PoCL's CPU device, integrated GPUs) can make its scene buffers over the
// prepared arrays themselves (CL_MEM_USE_HOST_PTR) instead of copying them,
// so that a big mesh's arrays are in memory once, not twice
// (render/device_buffers.hpp, docs/meshes.md). It may only where the
// array's address meets the device's base address alignment
// (CL_DEVICE_MEM_BASE_ADDR_ALIGN: 128 bytes on PoCL, which otherwise uses the
// pointer anyway and warns; Intel's runtimes want 4096 to avoid a copy),
// and malloc aligns a large block to 16 bytes only. A page covers them all.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace wp {

inline constexpr std::size_t kDeviceArrayAlignment = 4096;

// std::allocator, but every block starts on a kDeviceArrayAlignment boundary.
template <typename T> struct PageAlignedAllocator {
    using value_type = T;

    PageAlignedAllocator() = default;
    template <typename U> PageAlignedAllocator(const PageAlignedAllocator<U>&) noexcept {}

    T* allocate(std::size_t count) {
        return static_cast<T*>(
            ::operator new (count * sizeof(T), std::align_val_t{kDeviceArrayAlignment}));
    }
    void deallocate(T* block, std::size_t) noexcept {
        ::operator delete (block, std::align_val_t{kDeviceArrayAlignment});
    }

    template <typename U> bool operator==(const PageAlignedAllocator<U>&) const noexcept {
        return true;
    }
};

// A scene buffer's contents on the host (DeviceScene's members).
template <typename T> using DeviceArray = std::vector<T, PageAlignedAllocator<T>>;

} // namespace wp
