// Rendering on several devices at once (render/multi_device.hpp): the image
// equals a one-device render of the same samples up to float rounding, no
// sample is lost or counted twice, and a device that fails mid-render leaves
// a complete image from the others.
//
// The devices are sub-devices of the test device (PoCL's CPU split in two
// with clCreateSubDevices), or, where it cannot be split, the test device
// twice: each still gets its own context, queue, programs and buffers.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "render/chunk_source.hpp"
#include "render/multi_device.hpp"
#include "support/render_helpers.hpp"

using namespace wp;

namespace {

std::vector<DeviceInfo> two_devices() {
    static const std::vector<DeviceInfo> devices = [] {
        DeviceInfo parent = test::device_info();
        std::vector<DeviceInfo> out(2, parent);
        if (parent.compute_units >= 2) {
            const cl_device_partition_property equally[] = {
                CL_DEVICE_PARTITION_EQUALLY,
                static_cast<cl_device_partition_property>(parent.compute_units / 2), 0};
            std::vector<cl::Device> parts;
            try {
                parent.device.createSubDevices(equally, &parts);
            } catch (const cl::Error&) {
                parts.clear(); // no partitioning: the same device twice
            }
            for (std::size_t i = 0; i < out.size() && parts.size() >= out.size(); ++i) {
                out[i].device = parts[i];
                out[i].compute_units = parts[i].getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
            }
        }
        for (std::size_t i = 0; i < out.size(); ++i)
            out[i].device_index = static_cast<int>(100 + i); // tell them apart in messages
        return out;
    }();
    return devices;
}

// Float rounding is the only difference allowed: every sample's radiance is
// the same bits on either device (same kernels, same random numbers), and
// only the float32 sums on the device, over batches of at most `spp`
// samples, are grouped differently. Summing n non-negative floats rounds by
// at most (n - 1) * 2^-24 of their total, so two groupings of a pixel's
// samples differ by at most 2 * spp * 2^-24 of the pixel's sum, plus the
// rounding of the mean to float.
void check_same_image(const Film& multi, const Film& single, std::uint32_t spp) {
    REQUIRE(multi.pixel_count() == single.pixel_count());
    for (std::size_t p = 0; p < single.pixel_count(); ++p) {
        INFO("pixel " << p);
        REQUIRE(multi.samples(p) == spp); // none lost, none counted twice
        REQUIRE(single.samples(p) == spp);
    }
    const double relative = 2.0 * spp * std::ldexp(1.0, -24) + std::ldexp(1.0, -23);
    for (int parity : {-1, 1}) { // the mean, and the odd samples' mean
        Image a = parity < 0 ? multi.mean() : multi.half_mean(1);
        Image b = parity < 0 ? single.mean() : single.half_mean(1);
        std::size_t worst = 0;
        double worst_excess = -1.0;
        for (std::size_t i = 0; i < a.rgb.size(); ++i) {
            const double bound = relative * std::abs(b.rgb[i]) + 1e-37;
            const double excess = std::abs(a.rgb[i] - b.rgb[i]) / bound;
            if (excess > worst_excess) {
                worst_excess = excess;
                worst = i;
            }
        }
        INFO("worst value " << worst << ": " << a.rgb[worst] << " against " << b.rgb[worst]);
        CHECK(worst_excess <= 1.0);
    }
}

} // namespace

TEST_CASE("multi-device: chunks cover the samples once, shrink, and come back when given back") {
    const std::uint32_t first = 5, count = 100, workers = 3;
    ChunkQueue queue(first, count, workers);
    std::vector<SampleRange> taken;
    while (taken.size() < 3)
        taken.push_back(*queue.take());
    // Guided: each chunk is what is left over twice the workers.
    CHECK(taken[0].first == first);
    CHECK(taken[0].count == ChunkQueue::chunk_size(count, workers));
    CHECK(taken[0].count == 16);
    CHECK(taken[1].first == taken[0].first + taken[0].count);
    queue.give_back(taken[1]); // as a failed device does
    const SampleRange again = *queue.take();
    CHECK(again.first == taken[1].first);
    CHECK(again.count == taken[1].count);
    taken[1] = again;
    std::uint32_t previous = taken.back().count;
    std::optional<SampleRange> next;
    for (const SampleRange& range : taken)
        queue.complete(range);
    std::vector<bool> covered(count, false);
    for (const SampleRange& range : taken)
        for (std::uint32_t s = range.first; s < range.first + range.count; ++s) {
            REQUIRE_FALSE(covered[s - first]);
            covered[s - first] = true;
        }
    while ((next = queue.take())) {
        CHECK(next->count <= previous); // they shrink
        CHECK(next->count >= 1);
        previous = next->count;
        for (std::uint32_t s = next->first; s < next->first + next->count; ++s) {
            REQUIRE(s - first < count);
            REQUIRE_FALSE(covered[s - first]);
            covered[s - first] = true;
        }
        queue.complete(*next);
    }
    CHECK(std::count(covered.begin(), covered.end(), false) == 0);
    CHECK(previous == 1); // the last chunk is one sample per pixel
}

TEST_CASE("multi-device: two devices render the image one device renders, sample for sample") {
    const Scene scene = test::hexroom(24, 20);
    for (auto [regeneration, sampler] : {std::pair{false, Sampler::Independent},
                                         {true, Sampler::Independent},
                                         {false, Sampler::Sobol},
                                         {true, Sampler::Sobol}}) {
        INFO("regeneration " << regeneration << ", sampler " << to_string(sampler));
        const std::uint32_t spp = 16, seed = 7;
        IntegratorOptions options;
        options.seed = seed;
        options.regeneration = regeneration;
        options.sampler = sampler;
        test::Rendered single = test::render(scene, spp, seed, 0, options);

        MultiDeviceRenderer renderer(two_devices(), scene, options);
        REQUIRE(renderer.device_count() == 2);
        Film film(scene.camera.width, scene.camera.height);
        // Two calls, as the command's loop makes: the split may differ, the
        // samples may not.
        renderer.render(0, 9, film);
        renderer.render(9, spp - 9, film);
        check_same_image(film, single.film, spp);

        const std::vector<DeviceShare> shares = renderer.shares();
        REQUIRE(shares.size() == 2);
        const std::uint64_t pixels = film.pixel_count();
        CHECK(shares[0].samples + shares[1].samples == pixels * spp);
        CHECK(shares[0].samples > 0); // both took part
        CHECK(shares[1].samples > 0);
        CHECK(renderer.stats().camera_rays == pixels * spp);
        CHECK(renderer.stats().camera_rays == single.stats.camera_rays);
        CHECK(renderer.stats().shadow_rays == single.stats.shadow_rays);
    }
}

TEST_CASE("multi-device: the scene is prepared once, its hierarchy built once, for two devices") {
    // The hexroom traced through a hierarchy, which it would not need: the
    // counter tells one build from two.
    const Scene scene = test::hexroom(24, 20);
    const std::uint32_t spp = 8, seed = 3;
    IntegratorOptions options;
    options.seed = seed;
    options.traversal = Traversal::Hierarchy;
    test::Rendered single = test::render(scene, spp, seed, 0, options);

    const std::uint64_t before = scene_hierarchies_built();
    MultiDeviceRenderer renderer(two_devices(), scene, options);
    REQUIRE(renderer.device_count() == 2);
    CHECK(scene_hierarchies_built() == before + 1);
    CHECK(renderer.integrator().features().bvh);
    Film film(scene.camera.width, scene.camera.height);
    renderer.render(0, spp, film);
    check_same_image(film, single.film, spp);
    CHECK(renderer.shares()[0].samples > 0); // both took part
    CHECK(renderer.shares()[1].samples > 0);
}

TEST_CASE("multi-device: a device that fails mid-render leaves a complete, correct image") {
    const Scene scene = test::hexroom(24, 20);
    const std::uint32_t spp = 32, seed = 11;
    IntegratorOptions options;
    options.seed = seed;
    test::Rendered single = test::render(scene, spp, seed, 0, options);

    MultiDeviceRenderer renderer(two_devices(), scene, options);
    std::vector<std::string> reports;
    renderer.set_failure_reporter([&](const std::string& line) { reports.push_back(line); });
    renderer.fail_after_chunks(1, 1); // fails three quarters into its second chunk
    Film film(scene.camera.width, scene.camera.height);
    renderer.render(0, spp, film);
    check_same_image(film, single.film, spp);

    const std::vector<DeviceShare> shares = renderer.shares();
    CHECK(shares[0].error.empty());
    CHECK(shares[1].error.find("test hook") != std::string::npos);
    CHECK(shares[1].chunks == 1); // what it finished stays in the image
    CHECK(shares[1].samples > 0);
    CHECK(shares[0].samples + shares[1].samples == film.pixel_count() * spp);
    REQUIRE(reports.size() == 1);
    CHECK(reports[0].find(shares[1].index) != std::string::npos);
    CHECK(reports[0].find(shares[1].name) != std::string::npos);
    CHECK(renderer.device_count() == 1);

    // The survivor goes on alone in the next call.
    renderer.render(spp, 4, film);
    CHECK(film.min_samples() == spp + 4);
}

TEST_CASE("multi-device: when every device fails the render fails with their errors") {
    const Scene scene = test::hexroom(16, 16);
    MultiDeviceRenderer renderer(two_devices(), scene, IntegratorOptions{});
    renderer.set_failure_reporter([](const std::string&) {});
    renderer.fail_after_chunks(0, 0);
    renderer.fail_after_chunks(1, 0);
    Film film(16, 16);
    try {
        renderer.render(0, 8, film);
        FAIL("the render succeeded with every device failing");
    } catch (const std::runtime_error& e) {
        const std::string message = e.what();
        CHECK(message.find("every device failed") != std::string::npos);
        CHECK(message.find("0:100") != std::string::npos);
        CHECK(message.find("0:101") != std::string::npos);
    }
}
