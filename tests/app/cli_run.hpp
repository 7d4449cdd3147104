// Running the wavepath executable from a test as a user would: a scratch
// directory per test case, the command's exit code, stdout and stderr, and
// the check that a failure is one clear line.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "support/test_device.hpp"

namespace wp::test::cli {

namespace fs = std::filesystem;

struct Run {
    int exit_code = -1;
    std::string out;
    std::string err;
};

inline std::string slurp(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// A scratch directory per test case, removed at the end.
struct Scratch {
    fs::path dir;
    Scratch() {
        dir = fs::temp_directory_path() / ("wavepath-cli-" + std::to_string(::getpid()) + "-" +
                                           std::to_string(std::hash<std::string>{}(
                                               Catch::getResultCapture().getCurrentTestName())));
        fs::create_directories(dir);
    }
    ~Scratch() { fs::remove_all(dir); }
    fs::path write(const std::string& name, const std::string& text) const {
        std::ofstream(dir / name) << text;
        return dir / name;
    }
};

// The test device (support/test_device.hpp) as an index P:D.
inline const std::string& test_device_index() {
    static const std::string index = wp::test::device_info().index_string();
    return index;
}

// Runs the executable on the test device (WAVEPATH_DEVICE, unless --device
// says otherwise), so that it runs where the other tests do; `environment`
// (e.g. "WAVEPATH_CACHE_DIR='/tmp/x'") is prefixed to the shell command, after
// WAVEPATH_DEVICE, which it may therefore replace.
inline Run wavepath(const std::string& arguments, const Scratch& scratch,
                    const std::string& environment = "") {
    fs::path out = scratch.dir / "stdout.txt", err = scratch.dir / "stderr.txt";
    std::string command = "WAVEPATH_DEVICE='" + test_device_index() + "' " + environment + " '" +
                          WAVEPATH_EXE + "' " + arguments + " >'" + out.string() + "' 2>'" +
                          err.string() + "'";
    int status = std::system(command.c_str());
    Run run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    run.out = slurp(out);
    run.err = slurp(err);
    fs::remove(out);
    fs::remove(err);
    return run;
}

// One line, starting "wavepath: error:", that mentions `what`.
inline void check_one_line_error(const Run& run, const std::string& what) {
    INFO("stderr: " << run.err);
    CHECK(run.exit_code != 0);
    CHECK(run.exit_code < 128); // not killed by a signal
    CHECK(run.err.rfind("wavepath: error: ", 0) == 0);
    CHECK(run.err.find(what) != std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
}

inline const std::string kHexroom =
    std::string("'") + WAVEPATH_SOURCE_DIR + "/scenes/hexroom.json'";

} // namespace wp::test::cli
