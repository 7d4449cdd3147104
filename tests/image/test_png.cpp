// PNG output: decodes (with stb_image, independently of the writer) to the tone-mapped bytes.
#include "image/png.hpp"

#include "support/temp_dir.hpp"
#include "test_images.hpp"

#include <catch2/catch.hpp>

#include <stb/stb_image.h>

#include <cstdint>
#include <vector>

using wp::Image;
using wp::test::TempDir;

TEST_CASE("write_png stores the tone-mapped bytes, top row first", "[png]") {
    TempDir dir;
    Image img(3, 2);
    for (std::size_t i = 0; i < img.rgb.size(); ++i) {
        img.rgb[i] = static_cast<float>(i) / 17.0f; // distinct bytes per pixel and channel
    }
    for (const wp::ViewOptions view :
         {wp::ViewOptions{}, wp::ViewOptions::fixed(0.0, wp::ToneMap::Seed),
          wp::ViewOptions::fixed(-1.5), wp::ViewOptions::fixed(0.5, wp::ToneMap::Filmic)}) {
        wp::write_png(dir / "v.png", img, view);
        const std::vector<unsigned char> file = wp::test::read_bytes(dir / "v.png");
        int w = 0;
        int h = 0;
        int channels = 0;
        unsigned char* pixels =
            stbi_load_from_memory(file.data(), static_cast<int>(file.size()), &w, &h, &channels, 0);
        REQUIRE(pixels != nullptr);
        CHECK(w == 3);
        CHECK(h == 2);
        CHECK(channels == 3);
        const std::vector<std::uint8_t> decoded(pixels, pixels + w * h * 3);
        stbi_image_free(pixels);
        CHECK(decoded == wp::to_rgb8(img, view));
    }
    CHECK(dir.entries() == std::vector<std::string>{"v.png"});
}
