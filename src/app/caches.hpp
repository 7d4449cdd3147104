// The two on-disk caches a run of wavepath fills, kept bounded: wavepath's
// program cache (cl/program_cache.hpp) and PoCL's kernel cache, which PoCL
// writes for every program it builds or loads (bitcode, and a shared object
// per kernel and work-group size) and never trims.
#pragma once

#include <cstdint>

#include "render/integrator_options.hpp"

namespace wp {

inline constexpr std::uint64_t kProgramCacheMaxBytes = 256ull << 20;
inline constexpr std::uint64_t kPoclCacheMaxBytes = 512ull << 20;

// Before any OpenCL call. With the program cache on (`options`), trims it to
// kProgramCacheMaxBytes, oldest entries first, and, unless the user chose a
// place with POCL_CACHE_DIR, points PoCL's kernel cache at "pocl" inside it
// and trims that to kPoclCacheMaxBytes. With the cache off nothing is
// touched (--no-cache leaves every directory alone).
void prepare_caches(const IntegratorOptions& options);

} // namespace wp
