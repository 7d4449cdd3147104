// The two on-disk caches a run of wavepath fills, kept bounded: wavepath's
// program cache (cl/program_cache.hpp) and PoCL's kernel cache, which PoCL
// writes for every program it builds or loads (bitcode, and a shared object
// per kernel and work-group size) and never trims.
#pragma once

#include <chrono>
#include <cstdint>

#include "render/integrator_options.hpp"

namespace wp {

inline constexpr std::uint64_t kProgramCacheMaxBytes = 256ull << 20;
inline constexpr std::uint64_t kPoclCacheMaxBytes = 512ull << 20;
// PoCL's "tempfile_*" files older than this are leftovers: a compile writes
// and renames its own within seconds to minutes.
inline constexpr std::chrono::seconds kPoclTempfileMaxAge{60 * 60};

// Before any OpenCL call. With the program cache on (`options`), trims it to
// kProgramCacheMaxBytes, oldest entries first, and, unless the user chose a
// place with POCL_CACHE_DIR, points PoCL's kernel cache at "pocl" inside it
// and trims that to kPoclCacheMaxBytes, removing the temporary files PoCL
// left there more than kPoclTempfileMaxAge ago. With the cache off nothing is
// touched (--no-cache leaves every directory alone).
void prepare_caches(const IntegratorOptions& options);

} // namespace wp
