// write_image / read_image: format chosen by extension, clear errors otherwise.
#include "image/image_io.hpp"

#include "support/temp_dir.hpp"
#include "test_images.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

using wp::Image;
using wp::test::TempDir;

namespace {

std::vector<unsigned char> first_bytes(const std::filesystem::path& p, std::size_t n) {
    std::vector<unsigned char> bytes = wp::test::read_bytes(p);
    bytes.resize(std::min(bytes.size(), n));
    return bytes;
}

} // namespace

TEST_CASE("write_image picks the format from the extension, case-insensitively", "[io]") {
    TempDir dir;
    const Image img = wp::test::distinct_image(4, 3);
    wp::write_image(dir / "a.exr", img);
    wp::write_image(dir / "b.PFM", img);
    wp::write_image(dir / "c.Png", img);
    wp::write_image(dir / "d.EXR", img);
    CHECK(first_bytes(dir / "a.exr", 4) == std::vector<unsigned char>{0x76, 0x2f, 0x31, 0x01});
    CHECK(first_bytes(dir / "d.EXR", 4) == std::vector<unsigned char>{0x76, 0x2f, 0x31, 0x01});
    CHECK(first_bytes(dir / "b.PFM", 3) == std::vector<unsigned char>{'P', 'F', '\n'});
    CHECK(first_bytes(dir / "c.Png", 4) == std::vector<unsigned char>{0x89, 'P', 'N', 'G'});
    CHECK(wp::test::bit_identical(wp::read_image(dir / "a.exr"), img));
    CHECK(wp::test::bit_identical(wp::read_image(dir / "b.PFM"), img));
    CHECK(wp::test::bit_identical(wp::read_image(dir / "d.EXR"), img));
}

TEST_CASE("write_image rejects an unknown extension and writes nothing", "[io]") {
    TempDir dir;
    const Image img(1, 1);
    CHECK_THROWS_WITH(wp::write_image(dir / "out.xyz", img),
                      "cannot write '" + (dir / "out.xyz").string() +
                          "': unsupported image extension '.xyz' (use .exr, .pfm or .png)");
    CHECK_THROWS_WITH(wp::write_image(dir / "noext", img),
                      Catch::Contains("unsupported image extension ''"));
    CHECK_THROWS_AS(wp::write_image(dir / "out.jpg", img), wp::ImageError);
    CHECK(dir.entries().empty());
}

TEST_CASE("read_image reports missing files and unreadable formats", "[io]") {
    TempDir dir;
    const auto missing = dir / "nothing.exr";
    CHECK_THROWS_WITH(wp::read_image(missing),
                      "cannot open '" + missing.string() + "': No such file or directory");
    CHECK_THROWS_WITH(wp::read_image(dir / "nothing.pfm"),
                      Catch::Contains("No such file or directory"));
    wp::write_image(dir / "x.png", Image(1, 1));
    CHECK_THROWS_WITH(wp::read_image(dir / "x.png"),
                      Catch::Contains("unsupported image extension '.png' (use .exr or .pfm)"));
    std::filesystem::create_directory(dir / "sub.exr");
    CHECK_THROWS_WITH(wp::read_image(dir / "sub.exr"),
                      "cannot open '" + (dir / "sub.exr").string() + "': Is a directory");
}
