// `mpirun -np 2 wavepath render ...`: two ranks render the image one process
// renders, only rank 0 writes, and a rank that cannot start ends the job with
// its error. Skipped when wavepath was built without MPI or mpirun is absent.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "app/cli_run.hpp"
#include "app/same_samples.hpp"
#include "image/exr.hpp"
#include "image/image_io.hpp"
#include "support/sanitizer.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

namespace {

// mpirun with two ranks on this machine (more ranks than cores is fine), as
// root too (CI runs as root). In the sanitizer build the ranks run without
// LeakSanitizer: OpenMPI's components (plugins it loads and unloads again)
// leave allocations at exit whose frames are then unknown modules, which no
// suppression can name (docs/fuzzing.md); ASan's and UBSan's checks stay on.
std::string mpirun() {
    const std::string path = WAVEPATH_MPIRUN;
    if (path.empty() || !fs::exists(path))
        return {};
    const std::string environment =
        wp::test::kAddressSanitizer ? "ASAN_OPTIONS=\"${ASAN_OPTIONS:-}:detect_leaks=0\" " : "";
    return environment + "'" + path + "' --oversubscribe" +
           (::geteuid() == 0 ? " --allow-run-as-root" : "");
}

} // namespace

TEST_CASE("cli mpi: two ranks render the image one process renders") {
    const std::string launcher = mpirun();
    if (launcher.empty()) {
        WARN("skipped: wavepath was built without MPI, or mpirun is absent");
        return;
    }
    Scratch s;
    const std::uint32_t spp = 16;
    const std::string arguments = "render " + kHexroom + " --spp " + std::to_string(spp) +
                                  " --width 40 --height 30 --seed 4 --out ";
    const fs::path one = s.dir / "one.exr", two = s.dir / "two.exr";
    Run single = wavepath(arguments + "'" + one.string() + "'", s);
    INFO(single.err);
    REQUIRE(single.exit_code == 0);

    // cli_run's wavepath() runs the executable; here mpirun runs it twice.
    const fs::path out = s.dir / "mpi-out.txt", err = s.dir / "mpi-err.txt";
    const std::string command = "WAVEPATH_DEVICE='" + test_device_index() + "' " + launcher +
                                " -np 2 '" + WAVEPATH_EXE + "' " + arguments + "'" + two.string() +
                                "' >'" + out.string() + "' 2>'" + err.string() + "'";
    const int status = std::system(command.c_str());
    const std::string stdout_text = slurp(out), stderr_text = slurp(err);
    INFO(stderr_text);
    REQUIRE(status == 0);
    check_same_samples(wp::read_image(two), wp::read_image(one), spp);
    // Both ranks took part, and rank 0 printed the split (once).
    CHECK(stdout_text.find("\n1    ") != std::string::npos);
    CHECK(stdout_text.find("rendered ") == stdout_text.rfind("rendered "));
    // Rank 1 wrote nothing: the directory holds the two images and the logs.
    int files = 0;
    for (const auto& entry : fs::directory_iterator(s.dir))
        files += entry.is_regular_file();
    CHECK(files == 4);
}

TEST_CASE("cli mpi: a rank that cannot open its device ends the job with its error") {
    const std::string launcher = mpirun();
    if (launcher.empty()) {
        WARN("skipped: wavepath was built without MPI, or mpirun is absent");
        return;
    }
    Scratch s;
    const fs::path image = s.dir / "never.exr", err = s.dir / "mpi-err.txt";
    const std::string arguments =
        " render " + kHexroom + " --spp 2 --width 8 --height 8 --out '" + image.string() + "'";
    // Rank 1 alone looks for a device that does not exist.
    const std::string command = "WAVEPATH_DEVICE='" + test_device_index() + "' " + launcher +
                                " -np 1 '" + WAVEPATH_EXE + "'" + arguments +
                                " : -np 1 -x WAVEPATH_DEVICE=no-such-device '" + WAVEPATH_EXE +
                                "'" + arguments + " >/dev/null 2>'" + err.string() + "'";
    const int status = std::system(command.c_str());
    const std::string stderr_text = slurp(err);
    INFO(stderr_text);
    CHECK(status != 0);
    CHECK(stderr_text.rfind("wavepath: error: rank 1 of 2 (", 0) == 0); // the first line
    CHECK(stderr_text.find("no-such-device") != std::string::npos);
    CHECK_FALSE(fs::exists(image));
}

TEST_CASE("cli mpi: a rank that renders something else ends the job naming it and what differs") {
    const std::string launcher = mpirun();
    if (launcher.empty()) {
        WARN("skipped: wavepath was built without MPI, or mpirun is absent");
        return;
    }
    Scratch s;
    const fs::path image = s.dir / "never.exr", err = s.dir / "mpi-err.txt";
    const std::string rank0 =
        " render " + kHexroom + " --spp 2 --width 8 --height 8 --out '" + image.string() + "'";
    struct Case {
        std::string rank1_flags;
        std::string what;
    };
    for (const Case& c : {Case{" --path-types camera", "its options differ from rank 0's"},
                          Case{" --width 16", "its film is 16x8, rank 0's 8x8"}}) {
        INFO(c.rank1_flags);
        // Rank 1's arguments: rank 0's with its --width replaced, or more flags.
        std::string rank1 = rank0;
        if (c.rank1_flags.rfind(" --width", 0) == 0)
            rank1.replace(rank1.find(" --width 8"), 10, c.rank1_flags);
        else
            rank1 += c.rank1_flags;
        const std::string command = "WAVEPATH_DEVICE='" + test_device_index() + "' " + launcher +
                                    " -np 1 '" + WAVEPATH_EXE + "'" + rank0 + " : -np 1 '" +
                                    WAVEPATH_EXE + "'" + rank1 + " >/dev/null 2>'" + err.string() +
                                    "'";
        const int status = std::system(command.c_str());
        const std::string stderr_text = slurp(err);
        INFO(stderr_text);
        CHECK(status != 0);
        CHECK(stderr_text.rfind("wavepath: error: rank 1 of 2 (", 0) ==
              0); // the first line names the rank
        CHECK(stderr_text.find("does not render what rank 0 does: " + c.what) != std::string::npos);
        CHECK_FALSE(fs::exists(image));
    }
}

TEST_CASE("cli mpi: two ranks give the AOVs one process gives", "[aov]") {
    const std::string launcher = mpirun();
    if (launcher.empty()) {
        WARN("skipped: wavepath was built without MPI, or mpirun is absent");
        return;
    }
    Scratch s;
    const std::string arguments = "render " + kHexroom +
                                  " --spp 8 --width 24 --height 16 --seed 4 --aov "
                                  "albedo,normal,depth --out ";
    const fs::path one = s.dir / "one.exr", two = s.dir / "two.exr";
    Run single = wavepath(arguments + "'" + one.string() + "'", s);
    INFO(single.err);
    REQUIRE(single.exit_code == 0);
    const fs::path out = s.dir / "mpi-out.txt", err = s.dir / "mpi-err.txt";
    const std::string command = "WAVEPATH_DEVICE='" + test_device_index() + "' " + launcher +
                                " -np 2 '" + WAVEPATH_EXE + "' " + arguments + "'" + two.string() +
                                "' >'" + out.string() + "' 2>'" + err.string() + "'";
    const int status = std::system(command.c_str());
    const std::string stdout_text = slurp(out);
    INFO(slurp(err));
    REQUIRE(status == 0);
    CHECK(stdout_text.find("\n1    ") != std::string::npos); // rank 1 took part
    const auto a = wp::read_exr_channels(one), b = wp::read_exr_channels(two);
    REQUIRE(a.size() == 10);
    REQUIRE(b.size() == 10);
    for (const auto& [name, values] : a) {
        if (name.find('.') == std::string::npos)
            continue; // R, G, B: the test above
        INFO(name);
        const std::vector<float>& other = b.at(name);
        REQUIRE(other.size() == values.size());
        // Rank 1's share of a pixel's samples is in its AOVs: a lost share
        // would halve the mean, not move it by rounding.
        double worst = 0.0;
        for (std::size_t i = 0; i < values.size(); ++i)
            worst = std::max(worst, static_cast<double>(std::abs(values[i] - other[i])) /
                                        std::max(1.0, static_cast<double>(std::abs(values[i]))));
        CHECK(worst < 1e-5);
    }
}
