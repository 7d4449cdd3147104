// The wavepath executable as a child process that a test talks to while it
// runs (the live preview), with stdout and stderr in files of the scratch
// directory.
#pragma once

#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/cli_run.hpp"

extern char** environ;

namespace wp::test::cli {

class Child {
  public:
    // Runs wavepath with `arguments` on the test device.
    Child(const std::vector<std::string>& arguments, const Scratch& s)
        : out_(s.dir / "child-stdout.txt"), err_(s.dir / "child-stderr.txt") {
        std::vector<std::string> args = {WAVEPATH_EXE};
        args.insert(args.end(), arguments.begin(), arguments.end());
        args.push_back("--device");
        args.push_back(test_device_index());
        std::vector<char*> argv;
        for (std::string& a : args)
            argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 1, out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                         0644);
        posix_spawn_file_actions_addopen(&actions, 2, err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                         0644);
        const int rc = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        REQUIRE(rc == 0);
    }
    ~Child() {
        if (pid_ > 0) { // a failed test: do not leave it running
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
    }
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;

    // Waits (at most two minutes: the first kernel build is slow) until
    // stderr holds `text`; returns stderr.
    std::string wait_for_stderr(const std::string& text) const {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
        std::string err;
        while ((err = slurp(err_)).find(text) == std::string::npos) {
            INFO("stderr: " << err);
            REQUIRE(std::chrono::steady_clock::now() < deadline);
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return err;
    }

    // The wait status, within a minute.
    int wait() {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
        int status = 0;
        while (::waitpid(pid_, &status, WNOHANG) == 0) {
            REQUIRE(std::chrono::steady_clock::now() < deadline);
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        pid_ = 0;
        return status;
    }
    std::string out() const { return slurp(out_); }
    std::string err() const { return slurp(err_); }

  private:
    pid_t pid_ = 0;
    fs::path out_, err_;
};

} // namespace wp::test::cli
