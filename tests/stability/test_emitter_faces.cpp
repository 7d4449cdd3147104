// Case 12, emitters seen at grazing angles and from behind. Emitters are
// one-sided: a camera ray reads exactly Le from the front face at any angle
// (radiance, not intensity: nothing divides by the cosine) and exactly 0 from
// the back. A wall standing on a light's edge sees it at grazing angles, where
// next-event estimation's cosines go to 0: finite values only.
#include "stability.hpp"

using namespace wp;
using namespace wp::stability;

namespace {

// What each pixel of `scene`'s camera sees, from a fine grid over its area
// (the camera's jitter is uniform in the pixel), or kMixed: the scene is the
// emitter-faces one, whose surfaces are axis-aligned rectangles.
enum Seen { kFront = 0, kBack = 1, kWall = 2, kBackdrop = 3, kMixed = 4 };

std::vector<int> classify(const Scene& scene) {
    const Camera& cam = scene.camera;
    const int w = cam.width, h = cam.height, n = 16;
    D3 eye = cam.eye;
    D3 forward = normalize(cam.look_at - eye);
    D3 right = normalize(cross(forward, cam.up));
    D3 up = cross(right, forward);
    double ty = std::tan(cam.vertical_fov_degrees * M_PI / 360.0), tx = ty * w / h;
    auto first_hit = [&](const D3& d) {
        double best = INFINITY;
        int what = -1;
        auto rect = [&](int axis, double at, double lo0, double hi0, double lo1, double hi1,
                        int kind) {
            double o = eye[axis], dv = d[axis];
            if (dv == 0.0)
                return;
            double t = (at - o) / dv;
            if (t <= 0.0 || t >= best)
                return;
            D3 p = eye + d * t;
            double u = p[(axis + 1) % 3], v = p[(axis + 2) % 3];
            if (u >= lo0 && u <= hi0 && v >= lo1 && v <= hi1) {
                best = t;
                what = kind;
            }
        };
        rect(2, 0.0, -1, 1, -1, 1, kFront);   // z = 0: x, y in [-1, 1]
        rect(2, 1.0, -1, 1, 0.5, 2.5, kBack); // z = 1: x in [-1, 1], y in [0.5, 2.5]
        rect(0, 1.0, -1, 1, 0, 1.5, kWall);   // x = 1: y in [-1, 1], z in [0, 1.5]
        rect(0, 20.0, -30, 30, -30, 30, kBackdrop);
        return what;
    };
    std::vector<int> out;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int seen = -2;
            for (int j = 0; j < n && seen != kMixed; ++j)
                for (int i = 0; i < n; ++i) {
                    double sx = 2.0 * (x + (i + 0.5) / n) / w - 1.0;
                    double sy = 1.0 - 2.0 * (y + (j + 0.5) / n) / h;
                    int s = first_hit(forward + right * (sx * tx) + up * (sy * ty));
                    if (seen == -2)
                        seen = s;
                    else if (s != seen) {
                        seen = kMixed;
                        break;
                    }
                }
            out.push_back(seen);
        }
    // Only pixels whose eight neighbours see the same count: a sliver of
    // another surface (the grazing light tapers to nothing at its corners)
    // can hide between grid points.
    std::vector<int> eroded(out.size(), kMixed);
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            int s = out[static_cast<std::size_t>(y) * w + x];
            bool same = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    same = same && out[static_cast<std::size_t>(y + dy) * w + x + dx] == s;
            if (same)
                eroded[static_cast<std::size_t>(y) * w + x] = s;
        }
    return eroded;
}

struct Counts {
    int pixels[5] = {0, 0, 0, 0, 0};
    int wrong[5] = {0, 0, 0, 0, 0};
};

Counts check_exact(const Image& mean, const std::vector<int>& seen) {
    const float expected[4] = {10.0f, 0.0f, -1.0f, 1.0f}; // the wall: no exact value
    Counts c;
    for (std::size_t p = 0; p < seen.size(); ++p) {
        int s = seen[p];
        if (s < 0)
            continue;
        ++c.pixels[s];
        if (s < 4 && expected[s] >= 0.0f)
            for (int ch = 0; ch < 3; ++ch)
                if (mean.rgb[p * 3 + ch] != expected[s])
                    ++c.wrong[s];
    }
    return c;
}

} // namespace

TEST_CASE("emitters: the front face at 0.5 degrees reads exactly Le, the back face exactly 0",
          "[stability][emitter]") {
    Scene scene = stress_scene("emitter-faces", 64);
    for (bool nee : {true, false}) {
        INFO("next-event estimation " << nee);
        SECTION(nee ? "with next-event estimation" : "without next-event estimation") {
            IntegratorOptions options;
            options.next_event_estimation = nee;
            // The scene's view: every surface, the front light a band a
            // quarter of a pixel tall.
            test::Rendered r = test::render(scene, 16, 41, 0, options);
            Counts c = check_exact(r.film.mean(), classify(scene));
            CHECK(c.pixels[kBack] > 30);
            CHECK(c.wrong[kBack] == 0);
            CHECK(c.wrong[kBackdrop] == 0);
            CHECK(all_finite(r));

            // A 2 degree view of the front light's grazing band, 0.5 degrees
            // below the eye: whole rows of pixels on it.
            Scene grazing = scene;
            grazing.camera.vertical_fov_degrees = 2.0;
            test::Rendered g = test::render(grazing, 16, 42, 0, options);
            Counts cg = check_exact(g.film.mean(), classify(grazing));
            WARN("emitter faces (NEE " << nee << "): " << c.pixels[kBack] << " back-face pixels, "
                                       << c.wrong[kBack] << " not 0; " << cg.pixels[kFront]
                                       << " grazing front-face pixels, " << cg.wrong[kFront]
                                       << " not exactly 10; " << r.stats.nonfinite_samples << " + "
                                       << g.stats.nonfinite_samples << " non-finite");
            CHECK(cg.pixels[kFront] > 50);
            CHECK(cg.wrong[kFront] == 0);
            CHECK(all_finite(g));

            // Straight up at the second light's back from 0.7 below it: all of
            // it, every pixel exactly 0.
            Scene below = scene;
            below.camera =
                test::make_camera({0.0, 1.5, 0.3}, {0.0, 1.5, 1.0}, {0, 1, 0}, 60.0, 16, 16);
            test::Rendered b = test::render(below, 16, 44, 0, options);
            Counts cb = check_exact(b.film.mean(), classify(below));
            CHECK(cb.pixels[kBack] == 14 * 14); // all but the border the check leaves out
            CHECK(cb.wrong[kBack] == 0);
            Image mb = b.film.mean();
            CHECK(*std::max_element(mb.rgb.begin(), mb.rgb.end()) == 0.0f);
        }
    }
}

TEST_CASE("emitters: a wall on a light's edge, lit at grazing angles, stays finite",
          "[stability][emitter]") {
    // Looking at the wall x = 1 from in front of it, low: its bottom edge
    // touches the light, whose cosines there go to 0 and 1/d^2 to infinity.
    Scene scene = stress_scene("emitter-faces", 32);
    scene.camera = test::make_camera({-0.5, 0.0, 0.3}, {1.0, 0.0, 0.3}, {0, 0, 1}, 60.0, 32, 32);
    test::Rendered r = test::render(scene, 64, 43);
    Image mean = r.film.mean();
    float largest = 0.0f;
    for (float v : mean.rgb)
        largest = std::max(largest, v);
    WARN("wall on the light's edge: largest pixel " << largest << ", " << r.stats.nonfinite_samples
                                                    << " non-finite");
    CHECK(all_finite(r));
    CHECK(largest > 0.0f);
}
