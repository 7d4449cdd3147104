// The PNG view and the metadata of `wavepath render`, run as a user would:
// the automatic exposure shows bright, ordinary and dark scenes neither blown
// out nor black and does not depend on the scene's units; every output says
// how it was made, and `wavepath info` prints it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <stb/stb_image.h>

#include "app/cli_run.hpp"
#include "image/image_io.hpp"
#include "image/png_text.hpp"
#include "render/integrator_options.hpp"
#include "support/temp_dir.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

namespace {

const fs::path kScenes = fs::path(WAVEPATH_SOURCE_DIR) / "scenes";

std::string quoted(const fs::path& path) {
    return "'" + path.string() + "'";
}

// The hexroom with its light's radiance (100 in each channel) replaced.
fs::path hexroom_with_light(const Scratch& s, const std::string& name,
                            const std::string& radiance) {
    std::string text = slurp(kScenes / "hexroom.json");
    const std::string light = "\"radiance\": [100, 100, 100]";
    const std::size_t at = text.find(light);
    REQUIRE(at != std::string::npos);
    text.replace(at, light.size(),
                 "\"radiance\": [" + radiance + ", " + radiance + ", " + radiance + "]");
    return s.write(name, text);
}

// Renders scene small and fast to out.exr and out.png (with extra options).
void render(const fs::path& scene, const Scratch& s, const std::string& stem,
            const std::string& options = "") {
    const Run run = wavepath("render " + quoted(scene) + " --spp 8 --width 64 --height 64 --out " +
                                 quoted(s.dir / (stem + ".exr")) + " --png " +
                                 quoted(s.dir / (stem + ".png")) + " " + options,
                             s);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
}

// The PNG's pixels as stb_image decodes them (3 bytes each).
std::vector<unsigned char> decode_png(const fs::path& path) {
    int w = 0, h = 0, channels = 0;
    unsigned char* pixels = stbi_load(path.string().c_str(), &w, &h, &channels, 3);
    REQUIRE(pixels != nullptr);
    std::vector<unsigned char> out(pixels, pixels + w * h * 3);
    stbi_image_free(pixels);
    return out;
}

double rec709_luminance(double r, double g, double b) {
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

// The inverse of the sRGB transfer curve (IEC 61966-2-1).
double srgb_to_linear(unsigned char byte) {
    const double v = byte / 255.0;
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

struct ViewStats {
    double clipped = 0.0;          // fraction of non-emitter pixels with a channel at 255
    double median_luminance = 0.0; // of the non-emitter pixels, in display-linear units
    std::size_t non_emitter = 0;
};

// The view of the render in stem.exr/.png, over the pixels whose radiance is
// below emitter_luminance (those that do not see a light directly).
ViewStats view_stats(const Scratch& s, const std::string& stem, double emitter_luminance) {
    const wp::Image radiance = wp::read_image(s.dir / (stem + ".exr"));
    const std::vector<unsigned char> view = decode_png(s.dir / (stem + ".png"));
    REQUIRE(view.size() == radiance.rgb.size());
    ViewStats stats;
    std::size_t clipped = 0;
    std::vector<double> luminances;
    for (std::size_t p = 0; p < view.size(); p += 3) {
        const float* rgb = &radiance.rgb[p];
        if (rec709_luminance(rgb[0], rgb[1], rgb[2]) >= emitter_luminance)
            continue;
        clipped += view[p] == 255 || view[p + 1] == 255 || view[p + 2] == 255;
        luminances.push_back(rec709_luminance(srgb_to_linear(view[p]), srgb_to_linear(view[p + 1]),
                                              srgb_to_linear(view[p + 2])));
    }
    REQUIRE(!luminances.empty());
    stats.non_emitter = luminances.size();
    stats.clipped = static_cast<double>(clipped) / static_cast<double>(luminances.size());
    std::nth_element(luminances.begin(), luminances.begin() + luminances.size() / 2,
                     luminances.end());
    stats.median_luminance = luminances[luminances.size() / 2];
    return stats;
}

// Neither blown out nor black. The automatic exposure maps the median
// luminance of the pixels that see no light to mid grey (0.18), or lower
// where that would push more than 1 % of them past white, both as seen
// through a 3x3 median filter (image/exposure.hpp). So their displayed median
// is at most mid grey, with 15 % for byte rounding and for the median of
// displayed luminance not being the luminance of the median pixel; and not
// more than 3 stops under it (0.0225), darker than which a view reads as
// underexposed. Pixels with a channel at 255: the 1 % the filter lets pass,
// and, at 8 samples per pixel, pixels near the brightest regions that noise
// lifts past white on their own, and the partly covered pixels at a light's
// edge; 5 % bounds them, where the blown-out view this replaced (the hexroom
// at exposure 0) clips more than 20 % (checked below).
void check_well_exposed(const ViewStats& stats) {
    INFO("clipped " << stats.clipped << ", median display luminance " << stats.median_luminance
                    << " over " << stats.non_emitter << " pixels");
    CHECK(stats.clipped <= 0.05);
    CHECK(stats.median_luminance <= 0.18 * 1.15);
    CHECK(stats.median_luminance >= 0.18 / 8);
}

std::string metadata_value(const wp::Metadata& metadata, const std::string& name) {
    for (const auto& [key, text] : metadata)
        if (key == name)
            return text;
    FAIL("no metadata entry '" << name << "'");
    return {};
}

// The first line a shell command prints ("" if it fails).
std::string shell_line(const std::string& command) {
    std::string line;
    if (FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r")) {
        char buffer[512];
        if (std::fgets(buffer, sizeof buffer, pipe))
            line = buffer;
        if (::pclose(pipe) != 0)
            line.clear();
    }
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r'))
        line.pop_back();
    return line;
}

} // namespace

TEST_CASE("cli view: the hexroom, the Cornell box and a dark room are well exposed") {
    Scratch s;
    // Half the luminance of each scene's (only) light, as render computes it:
    // the hexroom's light is 100 in each channel, the Cornell box's (17, 12, 4).
    render(kScenes / "hexroom.json", s, "hexroom");
    check_well_exposed(view_stats(s, "hexroom", 50.0));
    render(kScenes / "cornell-box.json", s, "cornell");
    check_well_exposed(view_stats(s, "cornell", 0.5 * rec709_luminance(17, 12, 4)));
    render(hexroom_with_light(s, "dark.json", "0.1"), s, "dark");
    check_well_exposed(view_stats(s, "dark", 0.05));
    // --tonemap filmic uses the same exposure: no more clipped pixels, since
    // its curve only reaches white far past sRGB's.
    render(kScenes / "hexroom.json", s, "filmic", "--tonemap filmic");
    CHECK(view_stats(s, "filmic", 50.0).clipped <= view_stats(s, "hexroom", 50.0).clipped);

    // The views these checks tell apart from the automatic ones: the
    // hexroom at a fixed exposure of 0 (the old default) is blown out...
    render(kScenes / "hexroom.json", s, "blown", "--fixed-exposure 0");
    CHECK(view_stats(s, "blown", 50.0).clipped > 0.2);
    // ...and a fixed exposure does not adapt: at 0 stops the dark room (1000 times
    // dimmer than the hexroom, whose automatic exposure is near -1.5 stops)
    // shows about 8.5 stops under mid grey.
    render(hexroom_with_light(s, "dark.json", "0.1"), s, "dark-fixed", "--fixed-exposure 0");
    CHECK(view_stats(s, "dark-fixed", 0.05).median_luminance < 0.18 / 64);
}

TEST_CASE("cli view: scaling the light by 2^k leaves the automatic PNG unchanged") {
    Scratch s;
    // Powers of two scale every sample exactly (the paths and their random
    // numbers do not depend on the emission), so the EXRs differ by exactly 2^k.
    render(kScenes / "hexroom.json", s, "base");
    render(kScenes / "hexroom.json", s, "base-filmic", "--tonemap filmic");
    render(kScenes / "hexroom.json", s, "base-fixed", "--fixed-exposure -1");
    const std::vector<unsigned char> base = decode_png(s.dir / "base.png");
    for (const std::string& radiance : {std::string("0.09765625"), std::string("6400")}) {
        INFO("light radiance " << radiance << " instead of 100");
        const fs::path scene = hexroom_with_light(s, "scaled.json", radiance);
        render(scene, s, "scaled");
        CHECK(decode_png(s.dir / "scaled.png") == base);
        render(scene, s, "scaled-filmic", "--tonemap filmic");
        CHECK(decode_png(s.dir / "scaled-filmic.png") == decode_png(s.dir / "base-filmic.png"));
        render(scene, s, "scaled-fixed", "--fixed-exposure -1");
        CHECK(decode_png(s.dir / "scaled-fixed.png") != decode_png(s.dir / "base-fixed.png"));
    }
    // --exposure is an offset from the automatic exposure: +1 brightens.
    render(kScenes / "hexroom.json", s, "brighter", "--exposure 1");
    const std::vector<unsigned char> brighter = decode_png(s.dir / "brighter.png");
    std::size_t darker_pixels = 0;
    for (std::size_t i = 0; i < base.size(); ++i)
        darker_pixels += brighter[i] < base[i];
    CHECK(darker_pixels == 0);
    CHECK(brighter != base);
    const std::string view =
        metadata_value(wp::read_image_summary(s.dir / "brighter.png").metadata, "wavepath.view");
    CHECK(view.find("offset +1)") != std::string::npos);

    Run both = wavepath("render " + kHexroom + " --exposure 1 --fixed-exposure 0 --out " +
                            quoted(s.dir / "x.png"),
                        s);
    check_one_line_error(both, "--fixed-exposure");
    CHECK_FALSE(fs::exists(s.dir / "x.png"));
}

TEST_CASE("cli view: every output records how it was made, and info prints it") {
    Scratch s;
    const fs::path scene = s.write("room.json", slurp(kScenes / "hexroom.json"));
    const fs::path exr = s.dir / "out.exr", png = s.dir / "out.png";
    const Run run = wavepath("render " + quoted(scene) +
                                 " --spp 3 --seed 7 --width 16 --height 12 --light-sampling "
                                 "solid-angle --out " +
                                 quoted(exr) + " --png " + quoted(png),
                             s);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);

    // The scene's hash, from coreutils' sha256sum where it is installed.
    std::string hash = shell_line("sha256sum " + quoted(scene));
    hash = hash.substr(0, hash.find(' '));
    wp::IntegratorOptions options;
    options.seed = 7;
    options.light_sampling = wp::LightSampling::SolidAngle;
    std::smatch rate;
    REQUIRE(std::regex_search(run.out, rate, std::regex("s, ([0-9.e+]+) samples/s")));

    const wp::Metadata from_exr = wp::read_image(exr).metadata;
    const wp::Metadata from_png = wp::read_png_summary(wp::test::read_bytes(png), "png").metadata;
    for (const wp::Metadata* metadata : {&from_exr, &from_png}) {
        CHECK(metadata_value(*metadata, "wavepath.scene") == scene.string());
        if (hash.size() == 64)
            CHECK(metadata_value(*metadata, "wavepath.scene_sha256") == hash);
        else
            WARN("sha256sum not found: the scene hash is not checked");
        CHECK(metadata_value(*metadata, "wavepath.resolution") == "16x12");
        CHECK(metadata_value(*metadata, "wavepath.samples_per_pixel") == "3");
        CHECK(metadata_value(*metadata, "wavepath.samples_requested") == "3");
        CHECK(metadata_value(*metadata, "wavepath.seed") == "7");
        CHECK(metadata_value(*metadata, "wavepath.estimator") == wp::describe_estimator(options));
        CHECK(metadata_value(*metadata, "wavepath.estimator") == "cosine+nee+solid-angle");
        CHECK(metadata_value(*metadata, "wavepath.devices") == wp::test::device_info().name);
        CHECK(std::stod(metadata_value(*metadata, "wavepath.render_seconds")) >= 0.0);
        // The rate on stdout (3 digits) and in the file (4 digits) agree.
        CHECK(std::stod(metadata_value(*metadata, "wavepath.samples_per_second")) ==
              Approx(std::stod(rate[1])).epsilon(0.006));
        CHECK(!metadata_value(*metadata, "wavepath.version").empty());
        // The commit the executable was built from: HEAD, where the sources are a
        // git checkout with git installed, else "unknown".
        const std::string commit = metadata_value(*metadata, "wavepath.commit");
        const std::string head =
            shell_line("git -C " + quoted(WAVEPATH_SOURCE_DIR) + " rev-parse HEAD");
        if (head.empty()) {
            CHECK(commit == "unknown");
        } else {
            std::string hex = commit.substr(0, commit.find("-dirty"));
            if (const std::size_t g = hex.rfind("-g"); g != std::string::npos)
                hex = hex.substr(g + 2); // "tag-N-gHASH"
            INFO("commit '" << commit << "', HEAD " << head);
            CHECK(hex.size() >= 4);
            CHECK(head.rfind(hex, 0) == 0);
        }
    }
    CHECK(from_png.size() == from_exr.size() + 1); // and how the view was made
    CHECK(metadata_value(from_png, "wavepath.view").find("srgb, exposure ") == 0);

    // The PNG still decodes.
    CHECK(decode_png(png).size() == 16 * 12 * 3);

    // info prints them, one entry a line.
    for (const fs::path& image : {png, exr}) {
        const Run info = wavepath("info " + quoted(image), s);
        INFO(info.err);
        REQUIRE(info.exit_code == 0);
        CHECK(info.out.find("(" + std::string(image == png ? "PNG" : "OpenEXR") + ", 16x12)") !=
              std::string::npos);
        CHECK(std::regex_search(info.out, std::regex("\n  wavepath\\.seed +7\n")));
        CHECK(std::regex_search(info.out, std::regex("\n  wavepath\\.resolution +16x12\n")));
        CHECK(std::regex_search(info.out, std::regex("\n  wavepath\\.samples_per_pixel +3\n")));
        if (hash.size() == 64)
            CHECK(std::regex_search(info.out,
                                    std::regex("\n  wavepath\\.scene_sha256 +" + hash + "\n")));
    }
}

TEST_CASE("cli view: info on images without metadata says so") {
    Scratch s;
    wp::write_image(s.dir / "plain.exr", wp::Image(3, 2));
    wp::write_image(s.dir / "plain.pfm", wp::Image(3, 2));
    // A PNG with no text chunk: write_png's file with its chunks taken out.
    wp::write_image(s.dir / "view.png", wp::Image(3, 2), wp::ViewOptions::fixed(0.0));
    std::vector<unsigned char> bytes = wp::test::read_bytes(s.dir / "view.png");
    std::vector<unsigned char> plain(bytes.begin(), bytes.begin() + 33); // signature, IHDR
    for (std::size_t at = 33; at + 12 <= bytes.size();) {
        const std::size_t length = std::size_t{bytes[at]} << 24 | std::size_t{bytes[at + 1]} << 16 |
                                   std::size_t{bytes[at + 2]} << 8 | bytes[at + 3];
        if (std::string(bytes.begin() + static_cast<long>(at) + 4,
                        bytes.begin() + static_cast<long>(at) + 8) != "tEXt")
            plain.insert(plain.end(), bytes.begin() + static_cast<long>(at),
                         bytes.begin() + static_cast<long>(at + 12 + length));
        at += 12 + length;
    }
    wp::test::write_bytes(s.dir / "plain.png", plain);
    REQUIRE(wp::read_png_summary(plain, "plain").metadata.empty());

    for (const std::string name : {"plain.exr", "plain.png"}) {
        const Run info = wavepath("info " + quoted(s.dir / name), s);
        INFO(info.err);
        CHECK(info.exit_code == 0);
        CHECK(info.out.find("metadata: none\n") != std::string::npos);
    }
    const Run pfm = wavepath("info " + quoted(s.dir / "plain.pfm"), s);
    CHECK(pfm.exit_code == 0);
    CHECK(pfm.out.find("metadata: none (PFM files have no place for it)") != std::string::npos);
    check_one_line_error(wavepath("info " + quoted(s.dir / "missing.png"), s), "missing.png");
    s.write("broken.png", "\x89PNG\r\n\x1a\nnot really");
    check_one_line_error(wavepath("info " + quoted(s.dir / "broken.png"), s), "truncated PNG");
}
