// Ctrl-C during a long render, for real: the executable runs in a child
// process, gets SIGINT or SIGTERM once it is rendering, and must write its
// outputs with the samples done so far; a second signal ends it at once
// without leaving a temporary file.
#include <catch2/catch.hpp>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/child_process.hpp"
#include "app/cli_run.hpp"
#include "image/image_io.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

namespace {

const std::string kScene = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json";
constexpr const char* kManySamples = "1000000"; // hours: it ends only by the signal

std::vector<std::string> temporary_files(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.path().filename().string().find(".tmp") != std::string::npos)
            names.push_back(entry.path().string());
    return names;
}

} // namespace

TEST_CASE("cli: the first SIGINT or SIGTERM writes the outputs with the samples done") {
    const int sig = GENERATE(SIGINT, SIGTERM);
    Scratch s;
    const fs::path exr = s.dir / "out.exr", png = s.dir / "out.png";
    Child child({"render", kScene, "--width", "24", "--height", "16", "--spp", kManySamples,
                 "--out", exr.string(), "--png", png.string()},
                s);
    child.wait_until_rendering();
    child.signal(sig);
    const int status = child.wait();
    const std::string err = child.err();
    INFO("stderr: " << err);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 128 + sig);

    std::smatch match;
    REQUIRE(std::regex_search(err, match,
                              std::regex("the outputs hold ([0-9]+) of the 1000000 samples")));
    const long spp = std::stol(match[1]);
    CHECK(spp > 0);
    CHECK(spp < 1000000);
    // The summary on stdout gives the same count.
    CHECK(child.out().find("24x16, " + std::to_string(spp) + " spp") != std::string::npos);
    const wp::Image image = wp::read_image(exr);
    CHECK(image.width == 24);
    CHECK(image.height == 16);
    // The image says what it holds (test_cli_view.cpp checks the rest of its metadata).
    using Entry = std::pair<std::string, std::string>;
    for (const Entry& entry :
         std::vector<Entry>{{"wavepath.samples_per_pixel", std::to_string(spp)},
                            {"wavepath.samples_requested", kManySamples},
                            {"wavepath.seed", "0"}})
        CHECK(std::find(image.metadata.begin(), image.metadata.end(), entry) !=
              image.metadata.end());
    double sum = 0.0;
    for (const float v : image.rgb) {
        REQUIRE(std::isfinite(v));
        sum += v;
    }
    CHECK(sum > 0.0);
    CHECK(fs::file_size(png) > 0);
    CHECK(temporary_files(s.dir).empty());
}

TEST_CASE("cli: a second signal ends the render at once and leaves no temporary file") {
    Scratch s;
    const fs::path pfm = s.dir / "out.pfm";
    // A pool of 64 slots for 320x320 pixels: one sample per pixel takes 1600
    // waves, so the render is still in its wave when the second signal comes.
    Child child({"render", kScene, "--width", "320", "--height", "320", "--pool", "64", "--spp",
                 kManySamples, "--out", pfm.string()},
                s);
    child.wait_until_rendering();
    child.signal(SIGINT);
    // Signals sent back to back may merge into one: wait until the first has
    // been handled.
    child.wait_for_stderr("again to quit at once");
    child.signal(SIGINT);
    const int status = child.wait();
    INFO("stderr: " << child.err());
    REQUIRE(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == SIGINT);
    CHECK(temporary_files(s.dir).empty());
}

TEST_CASE("cli: an image that cannot be written after the render is saved elsewhere") {
    Scratch s;
    fs::create_directories(s.dir / "gone");
    const fs::path pfm = s.dir / "gone" / "out.pfm";
    Child child({"render", kScene, "--width", "24", "--height", "16", "--spp", kManySamples,
                 "--out", pfm.string()},
                s);
    child.wait_until_rendering();
    fs::remove_all(s.dir / "gone"); // after the checks, before the write
    child.signal(SIGINT);
    const int status = child.wait();
    const std::string err = child.err();
    INFO("stderr: " << err);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 1);
    std::smatch match;
    REQUIRE(std::regex_search(
        err, match,
        std::regex("wavepath: error: cannot write '[^']*out\\.pfm': .*the image was "
                   "saved to '([^']+)' instead\\n")));
    const fs::path fallback = match[1].str();
    CHECK(fallback.filename().string().find("out.pfm") != std::string::npos);
    REQUIRE(fs::exists(fallback));
    const wp::Image image = wp::read_image(fallback);
    CHECK(image.width == 24);
    fs::remove(fallback);
}

TEST_CASE("cli: a SIGINT during the final write still exits with 130, the outputs complete") {
    // The output is a FIFO whose reader waits: the image (128x64 floats x 3,
    // 98 kB) is more than the pipe holds (64 kB), so the write blocks midway
    // until the test reads, and the signal arrives after the last wave,
    // during the write. Before the fix the process then exited with 0.
    Scratch s;
    const fs::path fifo = s.dir / "out.pfm";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    // A reader already there: wavepath refuses a FIFO nobody reads.
    const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    REQUIRE(reader >= 0);
    Child child({"render", kScene, "--width", "128", "--height", "64", "--spp", "2", "--out",
                 fifo.string()},
                s);
    // Wait until the image begins to arrive: the render is over.
    pollfd ready{reader, POLLIN, 0};
    REQUIRE(::poll(&ready, 1, 300000) == 1);
    child.signal(SIGINT);
    std::this_thread::sleep_for(std::chrono::milliseconds(200)); // the signal is handled
    // Now read it all: the writer finishes, the process exits.
    ::fcntl(reader, F_SETFL, 0);
    std::string bytes;
    char buffer[65536];
    for (ssize_t n; (n = ::read(reader, buffer, sizeof buffer)) != 0;) {
        if (n < 0 && errno == EINTR)
            continue;
        REQUIRE(n > 0);
        bytes.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(reader);
    const int status = child.wait();
    const std::string err = child.err();
    INFO("stderr: " << err);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 130);
    CHECK(err.find("interrupted after the render: the outputs hold all 2 samples per pixel") !=
          std::string::npos);
    // The whole image came through: a PFM header and 128 x 64 x 3 floats.
    CHECK(bytes.rfind("PF\n128 64\n", 0) == 0);
    CHECK(bytes.size() > 128u * 64u * 3u * sizeof(float));
}

TEST_CASE("cli: commands other than render keep Ctrl-C's immediate effect") {
    Scratch s;
    Child child({"converge", kScene, "--width", "24", "--height", "16", "--max-spp", "16777216"},
                s);
    child.wait_for_stderr("kernels built in");
    child.signal(SIGINT);
    const int status = child.wait();
    INFO("stderr: " << child.err());
    REQUIRE(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == SIGINT);
}

TEST_CASE("cli: before the render has begun, the first signal ends the process at once") {
    Scratch s;
    // Empty kernel caches: the process spends seconds building kernels, and
    // the signal comes while it does (it is not rendering yet).
    const fs::path cache = s.dir / "cache", pocl = s.dir / "pocl";
    fs::create_directories(pocl);
    ::setenv("WAVEPATH_CACHE_DIR", cache.c_str(), 1);
    ::setenv("POCL_CACHE_DIR", pocl.c_str(), 1);
    Child child({"render", kScene, "--width", "8", "--height", "8", "--spp", kManySamples, "--out",
                 (s.dir / "never.exr").string()},
                s);
    ::unsetenv("WAVEPATH_CACHE_DIR");
    ::unsetenv("POCL_CACHE_DIR");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    if (child.err().find(" spp on ") != std::string::npos) {
        WARN("skipped: the kernels were built within half a second");
        child.signal(SIGKILL);
        child.wait();
        return;
    }
    const auto sent = std::chrono::steady_clock::now();
    child.signal(SIGTERM);
    const int status = child.wait();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
    INFO("stderr: " << child.err());
    CHECK(WIFSIGNALED(status)); // ended by the signal, not after a wave and the outputs
    CHECK((WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM));
    CHECK(seconds < 5.0);
    CHECK(child.err().find("finishing the current wave") == std::string::npos);
    CHECK_FALSE(fs::exists(s.dir / "never.exr"));
    CHECK(temporary_files(s.dir).empty());
}
