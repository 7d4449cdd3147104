// Golden images: renders of the hexroom and every loadable stress scene,
// under every estimator and launch variant, hashed bit for bit and compared
// with hashes stored in tests/data/golden-images.txt.
//
// Refactors that must not change a single pixel (the seam between host and
// kernels, the file layout of the kernels) are checked against these. The
// hashes are of the film's mean and variance images and of the ray and
// sample counts, so a change of rounding anywhere shows.
//
// Float rounding of built-in functions (sqrt, cos, normalize) may differ
// between OpenCL implementations and even CPU instruction sets, so the
// stored hashes belong to the devices named in the file's "# device:" lines
// (the one that recorded them, and any other shown to give the same bits, such
// as PoCL's skylake-avx512 code on an Intel Xeon and an AMD EPYC); on another
// device the test warns and checks nothing. After a change
// that is meant to alter images, record new hashes with
//   WAVEPATH_UPDATE_GOLDEN=1 ./build/wavepath_render_tests "golden*"
// and say why in the commit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "scene/load.hpp"
#include "support/render_helpers.hpp"

using namespace wp;

namespace {

const std::string kGoldenFile = std::string(WAVEPATH_SOURCE_DIR) + "/tests/data/golden-images.txt";

// FNV-1a over bytes, 64 bits.
struct Hash {
    std::uint64_t value = 0xcbf29ce484222325ull;
    void add(const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < bytes; ++i) {
            value ^= p[i];
            value *= 0x100000001b3ull;
        }
    }
    template <typename T> void add(const std::vector<T>& v) { add(v.data(), v.size() * sizeof(T)); }
    void add(std::uint64_t v) { add(&v, sizeof v); }
};

struct Case {
    std::string name;
    std::string scene; // path relative to the source directory
    IntegratorOptions options;
    int size = 16;
    std::uint32_t spp = 4;
};

std::vector<Case> cases() {
    std::vector<Case> out;
    const std::string hexroom = "scenes/hexroom.json";
    auto variant = [&](const std::string& name, auto&& change) {
        Case c{name, hexroom, {}};
        change(c.options);
        out.push_back(c);
    };
    variant("hexroom", [](IntegratorOptions&) {});
    variant("hexroom-general", [](IntegratorOptions& o) { o.general_kernels = true; });
    variant("hexroom-no-nee", [](IntegratorOptions& o) { o.next_event_estimation = false; });
    variant("hexroom-report",
            [](IntegratorOptions& o) { o.diffuse_sampling = DiffuseSampling::Report; });
    variant("hexroom-solid-angle",
            [](IntegratorOptions& o) { o.light_sampling = LightSampling::SolidAngle; });
    variant("hexroom-report-solid-angle-general", [](IntegratorOptions& o) {
        o.diffuse_sampling = DiffuseSampling::Report;
        o.light_sampling = LightSampling::SolidAngle;
        o.general_kernels = true;
    });
    variant("hexroom-regeneration-pool-37", [](IntegratorOptions& o) {
        o.regeneration = true;
        o.pool_size = 37;
    });
    variant("hexroom-max-depth-2", [](IntegratorOptions& o) { o.max_depth = 2; });
    // Next-event estimation alone at every vertex (--mis light): the estimator
    // the default was before Lambertian vertices were weighed by MIS, so its
    // hash is the hexroom's of then.
    variant("hexroom-mis-light", [](IntegratorOptions& o) { o.mis = MisStrategy::LightOnly; });
    // Every stress scene the loader accepts (the degenerate-* ones are refused).
    std::vector<std::string> stress;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/stress"))
        if (entry.path().extension() == ".json" &&
            entry.path().filename().string().rfind("degenerate-", 0) != 0)
            stress.push_back(entry.path().stem().string());
    std::sort(stress.begin(), stress.end());
    for (const std::string& name : stress)
        out.push_back({"stress-" + name, "scenes/stress/" + name + ".json", {}});
    // Its lights differ in radiance, so they are picked by power; by area
    // they render the image of before the power pick.
    Case area_pick{"stress-emitter-faces-area-pick", "scenes/stress/emitter-faces.json", {}};
    area_pick.options.light_pick = LightPick::Area;
    out.push_back(area_pick);
    return out;
}

std::uint64_t render_hash(const Case& c) {
    Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/" + c.scene);
    scene.camera.width = scene.camera.height = c.size;
    // The stages plan: the hashes pin its image; the fused plans are checked
    // against it in test_launch_plans.cpp (they agree bit for bit or within
    // the rounding of the film's float32 batches, which end elsewhere).
    IntegratorOptions options = c.options;
    options.launch_plan = LaunchPlan::Stages;
    test::Rendered r = test::render(scene, c.spp, 7, 0, options);
    Hash h;
    h.add(r.film.mean().rgb);
    h.add(r.film.variance_of_mean().rgb);
    h.add(r.film.half_mean(1).rgb);
    h.add(r.stats.camera_rays);
    h.add(r.stats.bounce_rays);
    h.add(r.stats.shadow_rays);
    h.add(r.stats.capped_paths);
    h.add(r.stats.nonfinite_samples);
    return h.value;
}

std::string hex(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

} // namespace

TEST_CASE("golden images: every scene and variant renders bit-identically to the stored hashes",
          "[golden]") {
    const std::string device = test::device().info.name;
    std::vector<Case> all = cases();
    REQUIRE(all.size() > 20);

    if (std::getenv("WAVEPATH_UPDATE_GOLDEN")) {
        std::ofstream out(kGoldenFile);
        out << "# device: " << device << "\n";
        for (const Case& c : all)
            out << c.name << ' ' << hex(render_hash(c)) << '\n';
        REQUIRE(out.good());
        WARN("recorded " << all.size() << " golden hashes in " << kGoldenFile);
        return;
    }

    std::ifstream in(kGoldenFile);
    REQUIRE(in.good());
    // Leading '#' lines: "# device: NAME" for each device these hashes hold on,
    // and comments.
    std::set<std::string> devices;
    std::string line;
    while (in.peek() == '#' && std::getline(in, line))
        if (line.rfind("# device: ", 0) == 0)
            devices.insert(line.substr(std::strlen("# device: ")));
    REQUIRE(!devices.empty());
    if (devices.count(device) == 0) {
        WARN("golden hashes were recorded on '" << *devices.begin() << "' (" << devices.size()
                                                << " device(s)), this is '" << device
                                                << "': not compared");
        return;
    }
    std::map<std::string, std::string> stored;
    for (std::string name, value; in >> name >> value;)
        stored[name] = value;
    REQUIRE(stored.size() == all.size());
    // The hashes tell the estimator variants apart (the general kernels render
    // exactly what the specialised ones do, tests/render/test_features.cpp,
    // so those two share one; so do scenes that render black).
    std::set<std::string> distinct;
    std::size_t variants = 0;
    for (const auto& [name, value] : stored)
        if (name.rfind("hexroom", 0) == 0 && name != "hexroom-general") {
            distinct.insert(value);
            ++variants;
        }
    CHECK(distinct.size() == variants);
    for (const Case& c : all) {
        INFO(c.name);
        REQUIRE(stored.count(c.name) == 1);
        CHECK(hex(render_hash(c)) == stored[c.name]);
    }
}
