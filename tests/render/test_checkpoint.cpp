// The checkpoint format (render/checkpoint.hpp): a film survives the round
// trip bit for bit, a render resumed from a checkpoint continues with the
// very sums of the uninterrupted one, and every file that does not belong to
// the render (another version, scene, resolution or options; damaged,
// truncated, not a checkpoint) is refused with one line naming why.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "cl/program_cache.hpp"
#include "render/checkpoint.hpp"
#include "support/render_helpers.hpp"
#include "support/temp_dir.hpp"

using namespace wp;

namespace {

constexpr int kWidth = 3;
constexpr int kHeight = 2;
constexpr std::uint32_t kSpp = 6;

// A film of kSpp samples per pixel with sums that use all of a double's bits
// (no two alike), as a render's would.
Film sample_film() {
    Film film(kWidth, kHeight);
    const std::size_t floats = static_cast<std::size_t>(kWidth) * kHeight * 4;
    for (std::uint32_t batch = 0; batch < kSpp / 2; ++batch) { // two samples a batch
        std::vector<float> sum(floats), squares(floats), odd(floats);
        for (std::size_t i = 0; i < floats; ++i) {
            const bool count = i % 4 == 3;
            sum[i] = count ? 2.0f : std::sqrt(static_cast<float>(i + 7 * batch + 1)) / 3.0f;
            squares[i] = count ? 0.0f : sum[i] * sum[i] * 1.1f;
            odd[i] = count ? 1.0f : sum[i] * 0.4f;
        }
        film.add_batch(sum, squares, odd);
    }
    return film;
}

CheckpointIdentity sample_identity() {
    return {0x0123456789abcdefull, kWidth, kHeight, "seed=3 max-depth=16 build=-D A=1",
            "wavepath test, kernels 0"};
}

void check_same_film(const Film& a, const Film& b) {
    const FilmSums x = a.sums(), y = b.sums();
    CHECK(a.width() == b.width());
    CHECK(a.height() == b.height());
    CHECK(x.sum == y.sum);
    CHECK(x.sum_squares == y.sum_squares);
    CHECK(x.odd_sum == y.odd_sum);
    CHECK(x.count == y.count);
    CHECK(x.odd_count == y.odd_count);
}

// The reason after "cannot resume from '<path>': ", checking that the
// message is one line of that form.
std::string refusal(const std::vector<unsigned char>& bytes) {
    try {
        decode_checkpoint(bytes, "c.wpck");
    } catch (const CheckpointError& e) {
        const std::string text = e.what();
        const std::string prefix = "cannot resume from 'c.wpck': ";
        REQUIRE(text.rfind(prefix, 0) == 0);
        REQUIRE(text.find('\n') == std::string::npos);
        return text.substr(prefix.size());
    }
    FAIL("accepted");
    return "";
}

// Rewrites the trailing checksum after an edit, so that a test reaches the
// checks behind it.
void reseal(std::vector<unsigned char>& bytes) {
    const std::uint64_t checksum = fnv1a64_bytes(bytes.data(), bytes.size() - 8);
    for (int i = 0; i < 8; ++i)
        bytes[bytes.size() - 8 + static_cast<std::size_t>(i)] =
            static_cast<unsigned char>(checksum >> (8 * i));
}

void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
}

} // namespace

TEST_CASE("checkpoint: a film and its identity survive the round trip bit for bit",
          "[checkpoint]") {
    const Film film = sample_film();
    const std::vector<unsigned char> bytes = encode_checkpoint(sample_identity(), kSpp, film);
    // The documented layout: 32 bytes of header, two texts, 11 numbers a pixel, the checksum.
    const CheckpointIdentity id = sample_identity();
    CHECK(bytes.size() ==
          32 + 4 + 4 + id.options.size() + id.version.size() + kWidth * kHeight * 11 * 8 + 8);
    CHECK(std::string(bytes.begin(), bytes.begin() + 8) == "WPCHKPT\n");

    const FilmCheckpoint back = decode_checkpoint(bytes, "c.wpck");
    CHECK(back.samples_per_pixel == kSpp);
    CHECK(back.identity.scene_hash == id.scene_hash);
    CHECK(back.identity.width == kWidth);
    CHECK(back.identity.height == kHeight);
    CHECK(back.identity.options == id.options);
    CHECK(back.identity.version == id.version);
    check_same_film(back.film, film);
    // The estimate too, of course.
    CHECK(back.film.mean().rgb == film.mean().rgb);
    CHECK(back.film.variance_of_mean().rgb == film.variance_of_mean().rgb);
}

TEST_CASE("checkpoint: a film with AOVs keeps them, 7 more numbers a pixel", "[checkpoint][aov]") {
    Film film = sample_film();
    const std::size_t pixels = static_cast<std::size_t>(kWidth) * kHeight;
    std::vector<float> albedo(pixels * 4), normal(pixels * 4), depth(pixels);
    for (std::size_t i = 0; i < pixels * 4; ++i) {
        albedo[i] = std::sqrt(static_cast<float>(i + 2));
        normal[i] = -std::sqrt(static_cast<float>(i + 3)) / 5.0f;
    }
    for (std::size_t p = 0; p < pixels; ++p)
        depth[p] = std::sqrt(static_cast<float>(p + 11)) * 7.0f;
    film.add_aov_batch(albedo, normal, depth);
    const std::vector<unsigned char> bytes = encode_checkpoint(sample_identity(), kSpp, film);
    const std::vector<unsigned char> plain =
        encode_checkpoint(sample_identity(), kSpp, sample_film());
    CHECK(bytes.size() == plain.size() + pixels * 7 * 8);
    const FilmCheckpoint back = decode_checkpoint(bytes, "c.wpck");
    check_same_film(back.film, film);
    REQUIRE(back.film.has_aovs());
    CHECK(back.film.sums().aov_sum == film.sums().aov_sum);
    for (std::uint32_t aov = 0; aov < 3; ++aov)
        CHECK(back.film.aov_mean(aov) == film.aov_mean(aov));
    CHECK_FALSE(decode_checkpoint(plain, "c.wpck").film.has_aovs());
    // One byte short of the AOVs is neither form: refused.
    std::vector<unsigned char> cut = bytes;
    cut.pop_back();
    CHECK_THROWS(decode_checkpoint(cut, "c.wpck"));
}

TEST_CASE("checkpoint: saved atomically and loaded for the same render", "[checkpoint]") {
    test::TempDir dir;
    const std::filesystem::path path = dir / "render.wpck";
    save_checkpoint(path, sample_identity(), kSpp, sample_film());
    save_checkpoint(path, sample_identity(), kSpp, sample_film());   // replaces it
    CHECK(dir.entries() == std::vector<std::string>{"render.wpck"}); // no temporary file left
    const FilmCheckpoint c = load_checkpoint(path, sample_identity());
    CHECK(c.samples_per_pixel == kSpp);
    check_same_film(c.film, sample_film());
}

TEST_CASE("checkpoint: one of another version, scene, resolution or options is refused",
          "[checkpoint]") {
    test::TempDir dir;
    const std::filesystem::path path = dir / "c.wpck";
    save_checkpoint(path, sample_identity(), kSpp, sample_film());
    const std::string prefix = "cannot resume from '" + path.string() + "': ";
    auto refused = [&](const CheckpointIdentity& expected) {
        try {
            load_checkpoint(path, expected);
        } catch (const CheckpointError& e) {
            const std::string text = e.what();
            REQUIRE(text.rfind(prefix, 0) == 0);
            REQUIRE(text.find('\n') == std::string::npos);
            return text.substr(prefix.size());
        }
        FAIL("accepted");
        return std::string();
    };
    CheckpointIdentity other = sample_identity();
    other.version = "wavepath 9.9, kernels 1";
    CHECK(refused(other) ==
          "it was written by wavepath test, kernels 0, and this is wavepath 9.9, kernels 1");
    other = sample_identity();
    other.scene_hash ^= 1;
    CHECK(refused(other) == "it is of another scene (scene hash 0123456789abcdef, this scene's "
                            "0123456789abcdee)");
    other = sample_identity();
    other.width = 4;
    CHECK(refused(other) == "it is of a 3x2 image, and this render is 4x2");
    other = sample_identity();
    other.options = "seed=4 max-depth=16 build=-D A=1";
    CHECK(refused(other) == "it was rendered with other options: seed=3, now seed=4");
    other.options = "seed=3 max-depth=16 build=-D A=0";
    CHECK(refused(other) == "it was rendered with other options: A=1, now A=0");
    other.options = "seed=3 max-depth=16 build=-D A=1 -D B=1";
    CHECK(refused(other) == "it was rendered with other options: (nothing), now -D B=1");
}

TEST_CASE("checkpoint: a missing, foreign, truncated or damaged file is refused", "[checkpoint]") {
    const std::vector<unsigned char> good =
        encode_checkpoint(sample_identity(), kSpp, sample_film());

    SECTION("missing") {
        test::TempDir dir;
        try {
            load_checkpoint(dir / "none.wpck", sample_identity());
            FAIL("accepted");
        } catch (const CheckpointError& e) {
            CHECK(std::string(e.what()) == "cannot resume from '" + (dir / "none.wpck").string() +
                                               "': No such file or directory");
        }
    }
    SECTION("not a checkpoint") {
        const std::string png = "\x89PNG\r\n\x1a\n and the rest of an image";
        CHECK(refusal({png.begin(), png.end()}) ==
              "not a wavepath checkpoint (no \"WPCHKPT\" at its start)");
        CHECK(refusal({}) == "not a wavepath checkpoint (no \"WPCHKPT\" at its start)");
    }
    SECTION("another format") {
        std::vector<unsigned char> bytes = good;
        bytes[8] = 2;
        CHECK(refusal(bytes).rfind("it has checkpoint format 2; this wavepath (wavepath ", 0) == 0);
    }
    SECTION("truncated anywhere") {
        // Every prefix of the file, from the bare magic on.
        for (std::size_t n = 8; n < good.size(); ++n) {
            INFO("first " << n << " of " << good.size() << " bytes");
            const std::string reason = refusal({good.begin(), good.begin() + static_cast<long>(n)});
            CHECK(reason.rfind("truncated: ", 0) == 0);
        }
        CHECK(refusal({good.begin(), good.end() - 1}) ==
              "truncated: " + std::to_string(good.size() - 1) + " of its " +
                  std::to_string(good.size()) + " bytes");
    }
    SECTION("bytes past its end") {
        std::vector<unsigned char> bytes = good;
        bytes.push_back(0);
        CHECK(refusal(bytes) == "damaged: 1 bytes past its end");
    }
    SECTION("any byte of the film or checksum flipped") {
        const std::size_t film_start = good.size() - 8 - kWidth * kHeight * 11 * 8;
        for (std::size_t i = film_start; i < good.size(); ++i) {
            std::vector<unsigned char> bytes = good;
            bytes[i] ^= 0x10;
            INFO("byte " << i);
            CHECK(refusal(bytes) == "damaged: its checksum does not match its contents");
        }
    }
    SECTION("a text's length garbled") {
        std::vector<unsigned char> bytes = good;
        bytes[35] = 0x7f; // the version's length, top byte
        CHECK(refusal(bytes) == "damaged: its version claims 2130706456 bytes");
    }
    SECTION("counts that disagree with the header, checksum resealed") {
        std::vector<unsigned char> bytes = good;
        const std::size_t counts = good.size() - 8 - kWidth * kHeight * 2 * 8;
        bytes[counts + 8 * 4] = static_cast<unsigned char>(kSpp + 1); // pixel 4's count
        reseal(bytes);
        CHECK(refusal(bytes) == "damaged: pixel 4 holds 7 samples, not the header's 6");
    }
    SECTION("non-finite sums, checksum resealed") {
        // A render never saves them (the kernels drop non-finite samples), and
        // resumed they would make a NaN image whose summary says no NaN.
        const std::size_t film_start = good.size() - 8 - kWidth * kHeight * 11 * 8;
        struct Poison {
            std::size_t value; // index among the 9 * pixels doubles
            std::uint64_t bits;
            std::string reason;
        };
        for (const Poison& p :
             {Poison{4, 0x7ff8000000000000ull, "damaged: pixel 1's sum is not finite (nan)"},
              Poison{18 + 17, 0x7ff0000000000000ull,
                     "damaged: pixel 5's sum of squares is not finite (inf)"},
              Poison{36, 0xfff0000000000000ull,
                     "damaged: pixel 0's odd-sample sum is not finite (-inf)"}}) {
            std::vector<unsigned char> bytes = good;
            for (int i = 0; i < 8; ++i)
                bytes[film_start + 8 * p.value + static_cast<std::size_t>(i)] =
                    static_cast<unsigned char>(p.bits >> (8 * i));
            reseal(bytes);
            CHECK(refusal(bytes) == p.reason);
        }
    }
    SECTION("through a file") {
        test::TempDir dir;
        std::vector<unsigned char> bytes(good.begin(), good.begin() + 100);
        write_bytes(dir / "short.wpck", bytes);
        CHECK_THROWS_WITH(load_checkpoint(dir / "short.wpck", sample_identity()),
                          Catch::StartsWith("cannot resume from '" + (dir / "short.wpck").string() +
                                            "': truncated: 100 of its "));
    }
}

TEST_CASE("checkpoint: the scene hash sees every change that alters the image", "[checkpoint]") {
    const Scene scene = test::hexroom(8, 8);
    const std::uint64_t h = scene_content_hash(scene);
    CHECK(scene_content_hash(scene) == h);
    Scene other = scene;
    other.camera.width = 16; // resolution is checked on its own, not hashed
    CHECK(scene_content_hash(other) == h);
    other = scene;
    Triangle nudged = other.triangles[3];
    nudged.v[1].x = std::nextafter(nudged.v[1].x, 1e9);
    other.triangles.set(3, nudged);
    CHECK(scene_content_hash(other) != h);
    other = scene;
    other.spheres[0].radius *= 1.0 + 1e-15;
    CHECK(scene_content_hash(other) != h);
    other = scene;
    other.materials[0].reflectance.y = 0.5;
    CHECK(scene_content_hash(other) != h);
    other = scene;
    other.camera.vertical_fov_degrees += 1e-9;
    CHECK(scene_content_hash(other) != h);
    // The lens and the filter.
    other = scene;
    other.camera.aperture_radius = 0.01;
    CHECK(scene_content_hash(other) != h);
    other.camera.focus_distance *= 2.0;
    CHECK(scene_content_hash(other) != scene_content_hash([&] {
              Scene s = other;
              s.camera.focus_distance = scene.camera.focus_distance;
              return s;
          }()));
    other = scene;
    other.camera.filter = FilterKind::Gaussian;
    CHECK(scene_content_hash(other) != h);
    other.camera.filter_stddev = 0.25;
    CHECK(scene_content_hash(other) != h);
    other = scene;
    other.camera.filter = FilterKind::Tent;
    const std::uint64_t tent = scene_content_hash(other);
    other.camera.filter_radius = 2.0;
    CHECK(scene_content_hash(other) != tent);
    other = scene;
    Triangle recoloured = other.triangles[0];
    recoloured.material =
        static_cast<std::uint32_t>((recoloured.material + 1) % other.materials.size());
    other.triangles.set(0, recoloured);
    CHECK(scene_content_hash(other) != h);
    other = scene;
    other.triangles.pop_back();
    CHECK(scene_content_hash(other) != h);
    // A rough plastic's every parameter, its kind included (table value 9).
    other = scene;
    other.materials[0].kind = MaterialKind::RoughPlastic;
    const std::uint64_t rough_plastic = scene_content_hash(other);
    CHECK(rough_plastic != h);
    const auto changed = [&](auto&& change) {
        Scene s = other;
        change(s.materials[0]);
        return scene_content_hash(s) != rough_plastic;
    };
    CHECK(changed([](Material& m) { m.alpha_u = m.alpha_v = 0.3; }));
    CHECK(changed([](Material& m) { m.distribution = MicrofacetDistribution::Ggx; }));
    CHECK(changed([](Material& m) { m.int_ior = 1.7; }));
    CHECK(changed([](Material& m) { m.ext_ior = 1.1; }));
    CHECK(changed([](Material& m) { m.specular.z = 0.5; }));
    CHECK(changed([](Material& m) { m.nonlinear = true; }));
}

TEST_CASE("checkpoint: a render resumed from a checkpoint has the uninterrupted render's sums",
          "[checkpoint]") {
    const Scene scene = test::hexroom(12, 8);
    IntegratorOptions options;
    options.seed = 9;
    WavefrontIntegrator integrator(test::device(), scene, options);
    const CheckpointIdentity id = checkpoint_identity(scene, options, integrator.program().options);

    Film whole(12, 8);
    for (std::uint32_t s = 0; s < 4; ++s)
        integrator.render(s, 1, whole);

    Film first(12, 8);
    for (std::uint32_t s = 0; s < 2; ++s)
        integrator.render(s, 1, first);
    test::TempDir dir;
    save_checkpoint(dir / "c.wpck", id, 2, first);
    FilmCheckpoint resumed = load_checkpoint(dir / "c.wpck", id);
    REQUIRE(resumed.samples_per_pixel == 2);
    for (std::uint32_t s = 2; s < 4; ++s)
        integrator.render(s, 1, resumed.film);
    check_same_film(resumed.film, whole);
    CHECK(resumed.film.mean().rgb == whole.mean().rgb);
}
