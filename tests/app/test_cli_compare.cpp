// `wavepath render --variance` and `wavepath compare --variance`: the test
// that two images differ by noise alone (the device kit's check of a GPU's
// images against PoCL's, docs/gpu.md).
#include <catch2/catch.hpp>

#include <string>

#include "app/cli_run.hpp"
#include "image/image_io.hpp"

using namespace wp::test::cli;

namespace {

// Built by append: GCC 12 warns (-Wrestrict, falsely) on "'" + string + "'".
std::string quoted(const fs::path& path) {
    std::string text = "'";
    return text.append(path.string()).append("'");
}

// An 8x8 render of the hexroom at 16 spp with `seed`: the image and its
// variance of the mean.
void render(const Scratch& s, int seed, const std::string& name) {
    const fs::path image = s.dir / (name + ".pfm"), variance = s.dir / (name + ".var.pfm");
    Run run = wavepath("render " + kHexroom + " --spp 16 --width 8 --height 8 --quiet --seed " +
                           std::to_string(seed) + " -o " + quoted(image) + " --variance " +
                           quoted(variance),
                       s);
    REQUIRE(run.exit_code == 0);
}

Run compare(const Scratch& s, const std::string& a, const std::string& b) {
    auto path = [&](const std::string& name) { return quoted(s.dir / name); };
    return wavepath("compare " + path(a + ".pfm") + " " + path(b + ".pfm") + " --variance " +
                        path(a + ".var.pfm") + " " + path(b + ".var.pfm"),
                    s);
}

} // namespace

TEST_CASE("cli: compare --variance passes noise and fails a bias") {
    Scratch s;
    render(s, 1, "a");
    render(s, 2, "b");

    Run same = compare(s, "a", "a");
    CHECK(same.exit_code == 0);
    CHECK(same.out.find("identical  192 of 192 values") != std::string::npos);
    CHECK(same.out.find(": pass") != std::string::npos);

    Run other = compare(s, "a", "b"); // another seed: noise only
    CHECK(other.exit_code == 0);
    CHECK(other.out.find(": pass") != std::string::npos);

    // Twice as bright, with the same variances: a bias the test must see.
    wp::Image doubled = wp::read_image(s.dir / "b.pfm");
    for (float& v : doubled.rgb)
        v *= 2.0f;
    wp::write_image(s.dir / "bright.pfm", doubled);
    fs::copy_file(s.dir / "b.var.pfm", s.dir / "bright.var.pfm");
    Run biased = compare(s, "a", "bright");
    CHECK(biased.exit_code == 1);
    CHECK(biased.out.find(": FAIL") != std::string::npos);
}
