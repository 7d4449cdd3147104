// Case 6, a light almost touching a surface: a 1 x 1 light facing down 1e-3
// above a diffuse floor. Next-event estimation's geometry term
// cos cos / d^2 reaches 1 / h^2 = 1e6 next to the light's edge, and its
// variance grows without bound as a floor point nears the edge: the pixels
// there see rare, huge samples. Nothing may become Inf or NaN, and the error
// against the exact image must keep falling as samples are added; the test
// measures how fast.
//
// The exact image: the floor (nothing else diffuse, and a plane cannot light
// itself) has radiance rho * Le * F(p), F the form factor from p to the
// light rectangle, averaged over each pixel's area on a fine grid. Pixels
// that see any of the light's (black) back are left out.
//
// Found here: shade.cl / lights.h compute the geometry term from the shadow
// ray's origin, which sits one ray offset o (2e-6 x the floor's size 20 =
// 4e-5) above the floor. Every visible floor point sees this light at grazing
// angles, where the term goes as the height squared: the image converges to
// that of a light at h - o, (1 - o / h)^2 = 0.92 of the right one (nearly
// uniformly: every visible floor point sees the light at grazing angles).
// The first test measures the noise's convergence after fitting one factor to
// the image; the second holds the image to the true one, which needs the
// geometry term taken at the surface point (docs/stability.md, case 6; the
// offset origin biased it by the factor above).
#include "stability.hpp"
#include "support/form_factor.hpp"

using namespace wp;
using namespace wp::stability;

namespace {

using test::rectangle_form_factor;

struct Exact {
    std::vector<double> radiance; // per pixel, green
    std::vector<bool> pure_floor; // every sub-sample of the pixel sees the floor
};

Exact exact_image(const Scene& scene, double rho, double le, double h, double half_side) {
    const Camera& cam = scene.camera;
    const int w = cam.width, hgt = cam.height, n = 48;
    D3 eye = cam.eye;
    D3 forward = normalize(cam.look_at - eye);
    D3 right = normalize(cross(forward, cam.up));
    D3 up = cross(right, forward);
    double ty = std::tan(cam.vertical_fov_degrees * M_PI / 360.0);
    double tx = ty * w / hgt;
    Exact e;
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0.0;
            bool pure = true;
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    double sx = 2.0 * (x + (i + 0.5) / n) / w - 1.0;
                    double sy = 1.0 - 2.0 * (y + (j + 0.5) / n) / hgt;
                    D3 d = forward + right * (sx * tx) + up * (sy * ty);
                    if (d.z >= 0.0) {
                        pure = false;
                        continue;
                    }
                    double tl = (h - eye.z) / d.z;
                    D3 pl = eye + d * tl;
                    if (std::abs(pl.x) <= half_side && std::abs(pl.y) <= half_side) {
                        pure = false; // the light's back: black
                        continue;
                    }
                    D3 p = eye + d * (-eye.z / d.z);
                    sum += rho * le *
                           rectangle_form_factor(-half_side - p.x, half_side - p.x,
                                                 -half_side - p.y, half_side - p.y, h);
                }
            e.radiance.push_back(sum / (n * n));
            e.pure_floor.push_back(pure);
        }
    return e;
}

struct ErrorStats {
    double scale = 1.0;             // the factor fitted to the image (1 when not fitted)
    double rms_relative = 0.0;      // pure-floor pixels not next to the light
    double edge_rms_relative = 0.0; // pure-floor pixels next to a pixel that sees the light
    double max_relative = 0.0;      // any pure-floor pixel
    double mean_sigmas = 0.0;       // mean over pure pixels vs exact, in standard errors
};

// Errors of the green channel against scale x exact, over the pixels that see
// only floor. With fit_scale, scale is fitted (ratio of the sums over pixels
// not next to the light), so that the errors measure the noise alone, not a
// bias that scales the whole image. Pixels next to the light (a neighbour
// sees some of it) sample floor points arbitrarily close to its edge, where
// the samples' tail is heaviest: their errors are reported apart.
ErrorStats errors(const Film& film, const Exact& e, bool fit_scale) {
    const int w = film.width(), h = film.height();
    Image mean = film.mean();
    Image variance = film.variance_of_mean();
    std::vector<int> kind(e.radiance.size(), 0); // 0: not floor, 1: body, 2: next to the light
    double film_sum = 0.0, exact_sum = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::size_t p = static_cast<std::size_t>(y) * w + x;
            if (!e.pure_floor[p])
                continue;
            bool edge = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    int nx = x + dx, ny = y + dy;
                    if (nx >= 0 && ny >= 0 && nx < w && ny < h &&
                        !e.pure_floor[static_cast<std::size_t>(ny) * w + nx])
                        edge = true;
                }
            kind[p] = edge ? 2 : 1;
            if (!edge) {
                film_sum += mean.rgb[p * 3 + 1];
                exact_sum += e.radiance[p];
            }
        }
    ErrorStats s;
    s.scale = fit_scale ? film_sum / exact_sum : 1.0;
    double sq = 0.0, edge_sq = 0.0, diff = 0.0, var = 0.0;
    int n = 0, edge_n = 0;
    for (std::size_t p = 0; p < kind.size(); ++p) {
        if (kind[p] == 0)
            continue;
        double expected = s.scale * e.radiance[p];
        double rel = (mean.rgb[p * 3 + 1] - expected) / expected;
        (kind[p] == 2 ? edge_sq : sq) += rel * rel;
        (kind[p] == 2 ? edge_n : n) += 1;
        s.max_relative = std::max(s.max_relative, std::abs(rel));
        diff += mean.rgb[p * 3 + 1] - expected;
        var += variance.rgb[p * 3 + 1];
    }
    s.rms_relative = std::sqrt(sq / n);
    s.edge_rms_relative = std::sqrt(edge_sq / std::max(1, edge_n));
    s.mean_sigmas = std::abs(diff) / std::sqrt(var);
    return s;
}

struct Ladder {
    std::vector<std::uint32_t> spp;
    std::vector<ErrorStats> stats;
    double slope = 0.0; // of log(rms relative error) against log(spp)
    std::uint64_t nonfinite = 0;
    bool finite = true;
    double seconds = 0.0;
    std::string describe() const {
        std::string out;
        for (std::size_t i = 0; i < spp.size(); ++i)
            out += std::to_string(spp[i]) + " spp: scale " + std::to_string(stats[i].scale) +
                   ", rms " + std::to_string(stats[i].rms_relative) + " (next to the light " +
                   std::to_string(stats[i].edge_rms_relative) + "), max " +
                   std::to_string(stats[i].max_relative) + ", mean off by " +
                   std::to_string(stats[i].mean_sigmas) + " sigma; ";
        return out + "slope " + std::to_string(slope) + "; " + std::to_string(nonfinite) +
               " non-finite; " + std::to_string(seconds) + " s";
    }
};

// Cumulative films of 16, 64, ... samples (same seed, consecutive sample
// ranges, so each extends the last), each compared with `exact`.
Ladder converge(const Scene& scene, const Exact& exact, std::uint32_t max_spp, bool fit_scale) {
    Ladder l;
    Film film(scene.camera.width, scene.camera.height);
    std::uint32_t done = 0;
    auto start = std::chrono::steady_clock::now();
    for (std::uint32_t spp = 16; spp <= max_spp; spp *= 4) {
        test::Rendered r = test::render(scene, spp - done, 31, done);
        film.merge(r.film);
        done = spp;
        l.nonfinite += r.stats.nonfinite_samples;
        l.finite = l.finite && all_finite(r);
        l.spp.push_back(spp);
        l.stats.push_back(errors(film, exact, fit_scale));
    }
    l.seconds = seconds_since(start);
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < l.spp.size(); ++i) {
        double lx = std::log(static_cast<double>(l.spp[i]));
        double ly = std::log(l.stats[i].rms_relative);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    const double k = static_cast<double>(l.spp.size());
    l.slope = (k * sxy - sx * sy) / (k * sxx - sx * sx);
    return l;
}

struct NearLightScene {
    Scene scene = stress_scene("light-near-surface", 32);
    double rho = 0.0, le = 0.0, h = 0.0;
    NearLightScene() {
        rho = scene.materials[0].reflectance.y;
        le = scene.materials[1].emission.y;
        h = scene.triangles[2].v[0].z;
    }
};

} // namespace

TEST_CASE("light 1e-3 above a floor: finite everywhere, and the error keeps falling with samples",
          "[stability][near-light][statistical]") {
    NearLightScene s;
    REQUIRE(s.h == 1e-3);
    // The noise alone: the image is compared after fitting one factor to it
    // (0.92 while the bias described above remains, then 1).
    Ladder l = converge(s.scene, exact_image(s.scene, s.rho, s.le, s.h, 0.5), 1024, true);
    WARN("light 1e-3 above the floor, relative error of pure-floor pixels after fitting a "
         "factor: "
         << l.describe());
    CHECK(l.nonfinite == 0);
    CHECK(l.finite);
    for (std::size_t i = 1; i < l.stats.size(); ++i)
        CHECK(l.stats[i].rms_relative < l.stats[i - 1].rms_relative);
    CHECK(l.slope < -0.4); // Monte Carlo's -0.5
    CHECK(l.stats.back().mean_sigmas < kSigmas);
    // The bias stays bounded: 0.99 now (0.91 with the geometry term taken at
    // the offset origin, 0.81 with a fixed 1e-4 offset, a tenth of the gap).
    CHECK(l.stats.back().scale > 0.85);
    CHECK(l.stats.back().scale < 1.05);
}

TEST_CASE("light 1e-3 above a floor: the direct light matches the exact image (geometry term "
          "from the surface point, docs/stability.md case 6)",
          "[stability][near-light][statistical]") {
    NearLightScene s;
    Ladder l = converge(s.scene, exact_image(s.scene, s.rho, s.le, s.h, 0.5), 1024, false);
    WARN("light 1e-3 above the floor, against the true image: " << l.describe());
    CHECK(l.stats.back().mean_sigmas < kSigmas);
    CHECK(l.stats.back().rms_relative < 0.05);
}
