// `wavepath export-mitsuba`: what it writes, what it refuses, and whether
// Mitsuba 3 renders the export to the image wavepath renders (the means of
// the whole image and of its four quadrants, per channel, within 5 combined
// standard errors). The Mitsuba part needs the `mitsuba` Python package and
// is skipped with a message without it.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli_run.hpp"
#include "support/render_helpers.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

namespace {

// Built by append: "'" + path + "'" trips GCC 12's false -Wrestrict.
std::string in_quotes(const fs::path& path) {
    std::string text = "'";
    return text.append(path.string()).append("'");
}

const std::string kScenes = WAVEPATH_SOURCE_DIR "/scenes/";

// The mean of a region of the image per channel, with its standard error.
struct RegionMean {
    std::array<double, 3> mean{};
    std::array<double, 3> standard_error{};
};

// The whole image, then the quadrants: top left, top right, bottom left,
// bottom right (row 0 at the top), as tools/mitsuba_render.py --blocks 2
// prints them.
using RegionMeans = std::array<RegionMean, 5>;

// wavepath's: from one render's per-pixel means and variances of the mean.
// Pixels are independent, so a region's mean over n pixels has variance
// sum(variance of each pixel's mean) / n^2.
RegionMeans wavepath_means(const wp::Film& film) {
    const wp::Image mean = film.mean();
    const wp::Image variance = film.variance_of_mean();
    const int w = film.width(), h = film.height();
    RegionMeans out;
    std::array<double, 5> pixels{};
    std::array<std::array<double, 3>, 5> sum{}, var{};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t p = (static_cast<std::size_t>(y) * w + x) * 3;
            for (std::size_t region :
                 {std::size_t(0), std::size_t(1 + (2 * y / h) * 2 + 2 * x / w)}) {
                pixels[region] += 1;
                for (std::size_t c = 0; c < 3; ++c) {
                    sum[region][c] += mean.rgb[p + c];
                    var[region][c] += variance.rgb[p + c];
                }
            }
        }
    for (std::size_t r = 0; r < 5; ++r)
        for (std::size_t c = 0; c < 3; ++c) {
            out[r].mean[c] = sum[r][c] / pixels[r];
            out[r].standard_error[c] = std::sqrt(var[r][c]) / pixels[r];
        }
    return out;
}

// Mitsuba's: tools/mitsuba_render.py's output, whose standard errors come
// from the spread of independent renders' means.
RegionMeans parse_mitsuba_means(const std::string& text) {
    RegionMeans out;
    std::istringstream lines(text);
    std::string line;
    std::size_t found = 0;
    while (std::getline(lines, line)) {
        std::istringstream in(line);
        std::string word, label_mean, label_error;
        in >> word;
        std::size_t region = 0;
        if (word == "block") {
            int row = 0, col = 0;
            in >> row >> col;
            region = 1 + static_cast<std::size_t>(row * 2 + col);
        } else if (word != "mean") {
            continue;
        }
        if (word == "block")
            in >> label_mean;
        RegionMean& r = out[region];
        in >> r.mean[0] >> r.mean[1] >> r.mean[2] >> label_error >> r.standard_error[0] >>
            r.standard_error[1] >> r.standard_error[2];
        REQUIRE(label_error == "standard_error");
        REQUIRE(in);
        ++found;
    }
    REQUIRE(found == 5);
    return out;
}

bool mitsuba_available() {
    return std::system("python3 -c 'import mitsuba' >/dev/null 2>&1") == 0;
}

// Exports the scene at `size` x `size`, renders the export with Mitsuba
// (`seeds` renders of `mitsuba_spp`) and the scene with wavepath
// (`wavepath_spp`), and compares the region means.
void check_against_mitsuba(const std::string& name, int size, int seeds, int mitsuba_spp,
                           std::uint32_t wavepath_spp) {
    INFO(name);
    Scratch s;
    const fs::path xml = s.dir / (name + ".xml");
    Run exported = wavepath("export-mitsuba " + in_quotes(kScenes + name + ".json") + " " +
                                in_quotes(xml) + " --width " + std::to_string(size) + " --height " +
                                std::to_string(size) + " --spp " + std::to_string(mitsuba_spp),
                            s);
    INFO(exported.err);
    REQUIRE(exported.exit_code == 0);

    const fs::path result = s.dir / "mitsuba.txt";
    const std::string command = "python3 '" WAVEPATH_SOURCE_DIR "/tools/mitsuba_render.py' " +
                                in_quotes(xml) + " --seeds " + std::to_string(seeds) +
                                " --blocks 2 >" + in_quotes(result) + " 2>&1";
    const int status = std::system(command.c_str());
    const std::string output = slurp(result);
    INFO("mitsuba_render.py: " << output);
    REQUIRE(status == 0);
    const RegionMeans mitsuba = parse_mitsuba_means(output);

    wp::Scene scene = wp::load_scene(kScenes + name + ".json");
    scene.camera.width = size;
    scene.camera.height = size;
    const RegionMeans ours = wavepath_means(wp::test::render(scene, wavepath_spp, 7).film);

    const char* regions[] = {"whole image", "top left", "top right", "bottom left", "bottom right"};
    for (std::size_t r = 0; r < 5; ++r)
        for (std::size_t c = 0; c < 3; ++c) {
            const double difference = ours[r].mean[c] - mitsuba[r].mean[c];
            const double sigma =
                std::hypot(ours[r].standard_error[c], mitsuba[r].standard_error[c]);
            INFO(regions[r] << ", channel " << c << ": wavepath " << ours[r].mean[c] << " +- "
                            << ours[r].standard_error[c] << ", Mitsuba " << mitsuba[r].mean[c]
                            << " +- " << mitsuba[r].standard_error[c] << ": " << difference / sigma
                            << " sigma, relative " << difference / mitsuba[r].mean[c]);
            CHECK(std::abs(difference) <= 5.0 * sigma);
            // Precise enough to catch a wrong colour, light or camera: the
            // whole image to 2.5 %, each quadrant to 10 % (5 sigma).
            CHECK(5.0 * sigma <= (r == 0 ? 0.025 : 0.10) * mitsuba[r].mean[c]);
        }
}

} // namespace

TEST_CASE("cli: export-mitsuba writes the XML and one PLY per material beside it",
          "[cli][export]") {
    Scratch s;
    const fs::path xml = s.dir / "box.xml";
    Run run = wavepath("export-mitsuba " + in_quotes(kScenes + "cornell-box.json") + " " +
                           in_quotes(xml) + " --spp 16 --width 20 --height 10",
                       s);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.empty());
    CHECK(run.out == "wrote " + xml.string() +
                         " (20x10, 16 spp) with 4 PLY meshes (38 triangles) and 0 spheres\n");
    const std::string text = slurp(xml);
    CHECK(text.find("<integer name=\"sample_count\" value=\"16\"/>") != std::string::npos);
    CHECK(text.find("<integer name=\"width\" value=\"20\"/>") != std::string::npos);
    CHECK(text.find("<integer name=\"height\" value=\"10\"/>") != std::string::npos);
    // The materials of the box in the file's order: white, red, green, light.
    for (const std::string mesh :
         {"box-0-white.ply", "box-1-red.ply", "box-2-green.ply", "box-3-light.ply"}) {
        CHECK(fs::is_regular_file(s.dir / mesh));
        CHECK(text.find("value=\"" + mesh + "\"") != std::string::npos);
    }
    // Nothing else: no temporary file left.
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(s.dir))
        files += entry.path().extension() == ".ply" || entry.path().extension() == ".xml";
    CHECK(files == 5);
}

TEST_CASE("cli: export-mitsuba refuses bad outputs and bad scenes before writing anything",
          "[cli][export]") {
    Scratch s;
    const std::string hexroom = slurp(kScenes + "hexroom.json");

    SECTION("the scene itself, through '..'") {
        const fs::path scene = s.write("scene.xml", hexroom); // a JSON scene named .xml
        fs::create_directories(s.dir / "sub");
        Run run = wavepath("export-mitsuba " + in_quotes(scene) + " " +
                               in_quotes(s.dir / "sub" / ".." / "scene.xml"),
                           s);
        check_one_line_error(run, "it is the same file as the scene");
        CHECK(slurp(scene) == hexroom);
        CHECK_FALSE(fs::exists(s.dir / "scene-0-back_left_wall.ply"));
    }
    SECTION("not .xml") {
        Run run = wavepath("export-mitsuba " + kHexroom + " " + in_quotes(s.dir / "out.json"), s);
        check_one_line_error(run, "unsupported extension '.json' (use .xml)");
        CHECK_FALSE(fs::exists(s.dir / "out.json"));
    }
    SECTION("a folder that does not exist") {
        Run run =
            wavepath("export-mitsuba " + kHexroom + " " + in_quotes(s.dir / "no" / "out.xml"), s);
        check_one_line_error(run, "does not exist");
    }
    SECTION("a mesh's name taken by a folder") {
        fs::create_directories(s.dir / "out-9-light.ply");
        Run run = wavepath("export-mitsuba " + kHexroom + " " + in_quotes(s.dir / "out.xml"), s);
        check_one_line_error(run, "out-9-light.ply");
        CHECK_FALSE(fs::exists(s.dir / "out.xml"));
        CHECK_FALSE(fs::exists(s.dir / "out-0-back_left_wall.ply"));
    }
    SECTION("a scene with an error") {
        const fs::path scene = s.write("bad.json", "{\"camera\": {}}");
        Run run =
            wavepath("export-mitsuba " + in_quotes(scene) + " " + in_quotes(s.dir / "out.xml"), s);
        check_one_line_error(run, "bad.json");
        CHECK_FALSE(fs::exists(s.dir / "out.xml"));
    }
    SECTION("no samples") {
        Run run = wavepath(
            "export-mitsuba " + kHexroom + " " + in_quotes(s.dir / "out.xml") + " --spp 0", s);
        CHECK(run.exit_code != 0);
        CHECK(run.err.find("--spp") != std::string::npos);
        CHECK_FALSE(fs::exists(s.dir / "out.xml"));
    }
}

TEST_CASE("cli: Mitsuba 3 renders the exported hexroom and Cornell box as wavepath does",
          "[cli][export][mitsuba]") {
    if (!mitsuba_available()) {
        WARN("skipped: the mitsuba Python package is not installed (pip install mitsuba)");
        return;
    }
    // Mitsuba: 16 renders of 64 spp, so each standard error comes from 15
    // degrees of freedom; wavepath: one render, its error from every pixel's
    // sample variance.
    check_against_mitsuba("hexroom", 32, 16, 64, 1024);
    check_against_mitsuba("cornell-box", 32, 16, 64, 1024);
}
