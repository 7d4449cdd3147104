// `wavepath render --checkpoint` and `--resume`, for real: a render gets a
// real SIGINT (or SIGKILL, which leaves only its periodic checkpoint),
// resumes to a total sample count, and its EXR must hold exactly the pixels
// of an uninterrupted render of that many samples with the same seed. And a
// checkpoint that is not this render's is refused in one line before any
// rendering.
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "app/child_process.hpp"
#include "app/cli_run.hpp"
#include "image/image_io.hpp"
#include "render/checkpoint.hpp"
#include "util/file.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

namespace {

const std::string kScene = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json";
const std::string kSize = " --width 24 --height 16";

std::string shell_quoted(const fs::path& p) {
    std::string text = "'";
    text += p.string();
    text += '\'';
    return text;
}

// The samples per pixel a finished or interrupted render's checkpoint holds.
long checkpoint_samples(const std::string& err) {
    std::smatch match;
    REQUIRE(std::regex_search(err, match, std::regex("checkpoint '[^']*' holds ([0-9]+) samples")));
    return std::stol(match[1]);
}

// An uninterrupted render of `spp` samples and the resumed one agree in every
// pixel, bit for bit (the metadata agree too: same spp, same seed).
void check_resumed_equals_uninterrupted(const Scratch& s, const fs::path& checkpoint, long spp,
                                        const std::string& options) {
    const fs::path resumed = s.dir / "resumed.exr", whole = s.dir / "whole.exr";
    const Run r = wavepath("render " + shell_quoted(kScene) + kSize + options + " --spp " +
                               std::to_string(spp) + " --resume " + shell_quoted(checkpoint) +
                               " --checkpoint " + shell_quoted(checkpoint) + " --out " +
                               shell_quoted(resumed),
                           s);
    INFO("resume stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    // Saving on where it started: the checkpoint now holds every sample.
    CHECK(checkpoint_samples(r.err) == spp);
    CHECK(r.err.find("resuming from '" + checkpoint.string() + "' at ") != std::string::npos);
    const Run w = wavepath("render " + shell_quoted(kScene) + kSize + options + " --spp " +
                               std::to_string(spp) + " --out " + shell_quoted(whole),
                           s);
    REQUIRE(w.exit_code == 0);
    const wp::Image a = wp::read_image(resumed), b = wp::read_image(whole);
    REQUIRE(a.width == 24);
    REQUIRE(b.width == 24);
    CHECK(a.rgb == b.rgb);
    // The metadata too, but for the run's time and speed, and where it
    // resumed from.
    const auto without_times = [](wp::Metadata metadata) {
        std::erase_if(metadata, [](const auto& entry) {
            return entry.first == "wavepath.render_seconds" ||
                   entry.first == "wavepath.samples_per_second" ||
                   entry.first == "wavepath.resumed_from";
        });
        return metadata;
    };
    CHECK(without_times(a.metadata) == without_times(b.metadata));
    double sum = 0.0;
    for (float v : a.rgb)
        sum += v;
    CHECK(sum > 0.0); // a real image, not two black ones
}

} // namespace

TEST_CASE("cli: a render interrupted by SIGINT and resumed equals the uninterrupted one") {
    // Without regeneration a call renders 1 sample per pixel, with it 8.
    const bool regeneration = GENERATE(false, true);
    const std::string seed = regeneration ? "4" : "3";
    const std::string options = " --seed " + seed + (regeneration ? " --regeneration" : "");
    INFO("options:" << options);
    Scratch s;
    const fs::path checkpoint = s.dir / "render.wpck";
    std::vector<std::string> arguments = {"render",       kScene,
                                          "--width",      "24",
                                          "--height",     "16",
                                          "--spp",        "1000000",
                                          "--out",        (s.dir / "part.exr").string(),
                                          "--checkpoint", checkpoint.string(),
                                          "--seed",       seed};
    if (regeneration)
        arguments.push_back("--regeneration");
    Child child(arguments, s);
    child.wait_until_rendering();
    child.signal(SIGINT);
    const int status = child.wait();
    INFO("stderr: " << child.err());
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) == 130);
    const long held = checkpoint_samples(child.err());
    REQUIRE(held > 0);
    // The interrupted outputs and the checkpoint hold the same samples.
    CHECK(child.err().find("the outputs hold " + std::to_string(held) + " of the 1000000") !=
          std::string::npos);
    // Resumed to a total that is not a multiple of the 8 a call renders
    // with regeneration, so that the last call is a short one.
    check_resumed_equals_uninterrupted(s, checkpoint, held + 5, options);
}

TEST_CASE("cli: a render killed outright resumes from its last periodic checkpoint") {
    Scratch s;
    const fs::path checkpoint = s.dir / "render.wpck";
    Child child({"render", kScene, "--width", "24", "--height", "16", "--spp", "1000000", "--out",
                 (s.dir / "part.exr").string(), "--checkpoint", checkpoint.string(),
                 "--checkpoint-every", "0.05", "--seed", "5"},
                s);
    child.wait_until_rendering();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    while (!fs::exists(checkpoint)) {
        REQUIRE(std::chrono::steady_clock::now() < deadline);
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200)); // a few more saves
    child.signal(SIGKILL);                                       // no chance to save at the end
    child.wait();
    // It wrote no image, and what it left is a whole checkpoint: saves are
    // atomic, so a kill in the middle of one leaves the previous checkpoint
    // (and, SIGKILL being uncatchable, the new one's temporary file beside it).
    CHECK(!fs::exists(s.dir / "part.exr"));
    const long held = wp::decode_checkpoint(wp::read_file_bytes(checkpoint), checkpoint.string())
                          .samples_per_pixel;
    REQUIRE(held > 0);
    check_resumed_equals_uninterrupted(s, checkpoint, held + 3, " --seed 5");
}

TEST_CASE("cli: a checkpoint of another render is refused before rendering") {
    Scratch s;
    const fs::path checkpoint = s.dir / "c.wpck", out = s.dir / "out.exr";
    const Run made = wavepath("render " + shell_quoted(kScene) + kSize +
                                  " --seed 3 --spp 2 --out " + shell_quoted(s.dir / "first.exr") +
                                  " --checkpoint " + shell_quoted(checkpoint),
                              s);
    REQUIRE(made.exit_code == 0);
    REQUIRE(checkpoint_samples(made.err) == 2);

    auto resume = [&](const std::string& scene, const std::string& arguments) {
        return wavepath("render " + shell_quoted(scene) + arguments + " --spp 4 --resume " +
                            shell_quoted(checkpoint) + " --out " + shell_quoted(out),
                        s);
    };
    auto refused = [&](const Run& run, const std::string& what) {
        check_one_line_error(run, "cannot resume from '" + checkpoint.string() + "': " + what);
        CHECK(!fs::exists(out)); // refused before any output
    };
    refused(resume(kScene, kSize + " --seed 4"),
            "it was rendered with other options: seed=3, now seed=4");
    refused(resume(kScene, kSize + " --seed 3 --no-nee"),
            "it was rendered with other options: estimator=cosine+nee+area, now "
            "estimator=cosine+no-nee");
    refused(resume(kScene, " --width 16 --height 16 --seed 3"),
            "it is of a 24x16 image, and this render is 16x16");
    std::string text = slurp(kScene);
    text.replace(text.find("\"fov\": 90"), 9, "\"fov\": 89");
    const fs::path other = s.write("other.json", text);
    refused(resume(other.string(), kSize + " --seed 3"), "it is of another scene (scene hash ");
    refused(wavepath("render " + shell_quoted(kScene) + kSize + " --seed 3 --spp 1 --resume " +
                         shell_quoted(checkpoint) + " --out " + shell_quoted(out),
                     s),
            "it holds 2 samples per pixel, more than --spp 1");
    // Damaged: cut short.
    fs::resize_file(checkpoint, fs::file_size(checkpoint) - 1);
    refused(resume(kScene, kSize + " --seed 3"), "truncated: ");
    // An output may not be the checkpoint it resumes from.
    const Run clash = wavepath("render " + shell_quoted(kScene) + kSize + " --spp 4 --resume " +
                                   shell_quoted(checkpoint) + " --out " + shell_quoted(out) +
                                   " --trace " + shell_quoted(checkpoint),
                               s);
    CHECK(clash.exit_code != 0);
    CHECK(clash.err.find("cannot write --trace '" + checkpoint.string() +
                         "': it is the same file as --resume") != std::string::npos);
}
