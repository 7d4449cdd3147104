#include "app/caches.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "cl/program_cache.hpp"
#include "util/cache_bound.hpp"

namespace wp {

void prepare_caches(const IntegratorOptions& options) {
    if (!options.program_cache.enabled)
        return;
    const std::filesystem::path dir = options.program_cache.directory.empty()
                                          ? default_program_cache_directory()
                                          : options.program_cache.directory;
    if (dir.empty())
        return;
    bound_cache(dir, CacheBound{kProgramCacheMaxBytes, 1, ".clbin", "", {}});
    if (const char* chosen = std::getenv("POCL_CACHE_DIR"); chosen != nullptr && *chosen != '\0')
        return; // the user's choice, and the user's to trim
    // PoCL reads the variable when the platform is first queried, which is
    // after this. Its entries are kcache/XX/HASH/: two levels down.
    const std::filesystem::path pocl = dir / "pocl";
    std::error_code ec;
    std::filesystem::create_directories(pocl, ec);
    if (ec)
        return; // PoCL keeps its default place
    ::setenv("POCL_CACHE_DIR", pocl.c_str(), 1);
    bound_cache(pocl, CacheBound{kPoclCacheMaxBytes, 2, "", "tempfile_", kPoclTempfileMaxAge});
}

} // namespace wp
