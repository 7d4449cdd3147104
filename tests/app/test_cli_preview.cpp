// The live preview of `wavepath render --preview` (app/preview_server.hpp):
// what it serves while the render runs, the page in a real browser
// (headless Chromium, skipped when absent), and its stop button.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <httplib.h>
#include <stb_image.h>

#include "app/child_process.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "image/tonemap.hpp"
#include "support/render_helpers.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

namespace {

const std::string kScene = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json";
constexpr const char* kManySamples = "1000000"; // hours: it ends only by the stop

// Where the render serves its preview: the port, and the URL's path with
// its per-run token ("/0123.../").
struct Preview {
    int port = 0;
    std::string base;
    std::string url() const { return "http://127.0.0.1:" + std::to_string(port) + base; }
};

// The preview the render prints when it starts serving.
Preview preview_of(const Child& child) {
    const std::string err = child.wait_for_stderr("/ (its Stop button");
    std::smatch match;
    REQUIRE(std::regex_search(
        err, match, std::regex("preview at http://127\\.0\\.0\\.1:([0-9]+)(/[0-9a-f]{32}/)")));
    return {std::stoi(match[1]), match[2]};
}

std::string get(const Preview& preview, const std::string& path) {
    httplib::Client client("127.0.0.1", preview.port);
    const httplib::Result result = client.Get((preview.base + path).c_str());
    REQUIRE(result);
    REQUIRE(result->status == 200);
    return result->body;
}

// A number field of the status JSON; NaN for null or absent.
double status_field(const std::string& status, const std::string& name) {
    std::smatch match;
    if (!std::regex_search(status, match, std::regex("\"" + name + "\": ([-0-9.e+]+)")))
        return std::nan("");
    return std::stod(match[1]);
}

// Polls /status.json until the render holds at least `spp` samples per pixel.
void wait_for_spp(const Preview& preview, double spp) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
    while (!(status_field(get(preview, "status.json"), "spp") >= spp)) {
        REQUIRE(std::chrono::steady_clock::now() < deadline);
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
}

struct Rgb8 {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
};

Rgb8 decode_png(const std::string& bytes) {
    Rgb8 image;
    int channels = 0;
    unsigned char* pixels = stbi_load_from_memory(
        reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size()),
        &image.width, &image.height, &channels, 3);
    REQUIRE(pixels != nullptr);
    image.rgb.assign(pixels, pixels + static_cast<std::size_t>(image.width) * image.height * 3);
    stbi_image_free(pixels);
    return image;
}

void post_stop(const Preview& preview) {
    httplib::Client client("127.0.0.1", preview.port);
    const httplib::Result result = client.Post((preview.base + "stop").c_str());
    REQUIRE(result);
    CHECK(result->status == 200);
    CHECK(result->body == "stopping\n");
}

std::string metadata_spp(const fs::path& image_path) {
    for (const auto& [key, value] : wp::read_image(image_path).metadata)
        if (key == "wavepath.samples_per_pixel")
            return value;
    return "";
}

// Pearson's correlation of two equally long byte sequences.
double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    const double n = static_cast<double>(a.size());
    double mean_a = 0.0, mean_b = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        mean_a += a[i] / n;
        mean_b += b[i] / n;
    }
    double ab = 0.0, aa = 0.0, bb = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ab += (a[i] - mean_a) * (b[i] - mean_b);
        aa += (a[i] - mean_a) * (a[i] - mean_a);
        bb += (b[i] - mean_b) * (b[i] - mean_b);
    }
    return ab / std::sqrt(aa * bb);
}

// The stop's end: exit code as after Ctrl-C, the outputs written with the
// samples done (at least `at_least`).
void check_stopped(Child& child, const fs::path& exr, long at_least) {
    const int status = child.wait();
    const std::string err = child.err();
    INFO("stderr: " << err);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 130);
    CHECK(err.find("stop asked for on the preview page") != std::string::npos);
    std::smatch match;
    REQUIRE(std::regex_search(err, match,
                              std::regex("the outputs hold ([0-9]+) of the 1000000 samples")));
    const long spp = std::stol(match[1]);
    CHECK(spp >= at_least);
    CHECK(metadata_spp(exr) == std::to_string(spp));
}

} // namespace

TEST_CASE("cli: the preview serves the current image and status, and POST /stop ends the render") {
    Scratch s;
    const fs::path exr = s.dir / "out.exr", png = s.dir / "out.png";
    Child child({"render", kScene, "--width", "48", "--height", "32", "--spp", kManySamples,
                 "--quiet", "--out", exr.string(), "--png", png.string(), "--preview", "0"},
                s);
    const Preview preview = preview_of(child);
    wait_for_spp(preview, 4);

    // An image and the status published with it: the spp before and after
    // fetching the image agree (a publish comes at most once a second).
    std::string status, image_bytes;
    for (int attempt = 0;; ++attempt) {
        REQUIRE(attempt < 20);
        status = get(preview, "status.json");
        image_bytes = get(preview, "image.png");
        if (status_field(get(preview, "status.json"), "spp") == status_field(status, "spp"))
            break;
    }
    INFO("status: " << status);
    CHECK(status.find("\"state\": \"rendering\"") != std::string::npos);
    CHECK(status_field(status, "width") == 48);
    CHECK(status_field(status, "height") == 32);
    CHECK(status_field(status, "samples_per_second") > 0.0);
    const auto spp = static_cast<std::uint32_t>(status_field(status, "spp"));
    REQUIRE(spp >= 4);

    // The same render in this process (same device and seed, one sample per
    // call): the PNG is its mean, tone mapped, byte for byte, and the error
    // is its half images' estimate.
    const wp::Scene scene = wp::test::hexroom(48, 32);
    wp::WavefrontIntegrator integrator(wp::test::device(), scene, wp::IntegratorOptions{});
    wp::Film film(48, 32);
    for (std::uint32_t done = 0; done < spp; ++done)
        integrator.render(done, 1, film);
    const Rgb8 shown = decode_png(image_bytes);
    CHECK(shown.width == 48);
    CHECK(shown.height == 32);
    // The view the render uses: automatic exposure leaving out the pixels
    // at half the hexroom light's luminance (100) or more (app/view_cli.hpp).
    wp::ViewOptions view;
    view.emitter_luminance = 50.0;
    CHECK(shown.rgb == wp::to_rgb8(film.mean(), view));
    const double estimate =
        wp::rel_mse_from_halves(film.half_mean(0), film.half_mean(1), spp - spp / 2, spp / 2);
    CHECK(status_field(status, "rel_mse") == Approx(estimate).epsilon(1e-5)); // 6 digits

    const std::string page = get(preview, "");
    CHECK(page.find("<img id=\"view\"") != std::string::npos);
    CHECK(page.find("\"status.json\"") != std::string::npos);

    post_stop(preview);
    check_stopped(child, exr, spp);
    CHECK(fs::file_size(png) > 0);
}

TEST_CASE("cli: the preview page shows the image in a browser") {
    if (std::system("command -v chromium >/dev/null 2>&1") != 0) {
        WARN("skipped: chromium is not installed (bash tools/install-deps.sh --ci installs it)");
        return;
    }
    Scratch s;
    const fs::path exr = s.dir / "out.exr", final_png = s.dir / "final.png";
    const int width = 64, height = 48;
    Child child({"render", kScene, "--width", std::to_string(width), "--height",
                 std::to_string(height), "--spp", kManySamples, "--quiet", "--out", exr.string(),
                 "--png", final_png.string(), "--preview", "0"},
                s);
    const Preview preview = preview_of(child);
    wait_for_spp(preview, 16);

    // Headless, a few seconds of the page's own time: it polls the status
    // and loads the image. --no-sandbox: Chromium's sandbox refuses root.
    const int window_width = 800, window_height = 560;
    const fs::path shot = s.dir / "shot.png";
    const std::string command =
        "chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=" +
        std::to_string(window_width) + "," + std::to_string(window_height) +
        " --virtual-time-budget=3000 --screenshot='" + shot.string() + "' " + preview.url() +
        " >'" + (s.dir / "chromium.txt").string() + "' 2>&1";
    const int browser = std::system(command.c_str());
    INFO("chromium: " << slurp(s.dir / "chromium.txt"));
    REQUIRE(browser == 0);
    post_stop(preview);
    check_stopped(child, exr, 16);

    const Rgb8 screen = decode_png(slurp(shot));
    REQUIRE(screen.width == window_width);
    REQUIRE(screen.height == window_height);
    const auto at = [&screen](int x, int y, int c) {
        return static_cast<double>(
            screen.rgb[(static_cast<std::size_t>(y) * screen.width + x) * 3 + c]);
    };
    // The page's layout (app/preview_page.hpp): the image at (8, 48), scaled
    // by the largest whole factor that fits, on a #202020 background.
    const int scale = std::min((window_width - 16) / width, (window_height - 56) / height);
    REQUIRE(scale >= 2);
    const int right = 8 + width * scale;
    int background = 0, elsewhere = 0;
    for (int y = 48; y < window_height; ++y)
        for (int x = right + 4; x < window_width; ++x, ++elsewhere)
            background += at(x, y, 0) == 32 && at(x, y, 1) == 32 && at(x, y, 2) == 32;
    CHECK(background == elsewhere);

    // Each image pixel's block, at its centre, against the final image: the
    // same picture, earlier in its convergence (noisier), so strongly
    // correlated; a blank, shifted or wrong image is not.
    const Rgb8 final_image = decode_png(slurp(final_png));
    std::vector<double> on_screen, rendered;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                on_screen.push_back(at(8 + x * scale + scale / 2, 48 + y * scale + scale / 2, c));
                rendered.push_back(
                    final_image.rgb[(static_cast<std::size_t>(y) * width + x) * 3 + c]);
            }
    const double r = correlation(on_screen, rendered);
    INFO("correlation " << r);
    CHECK(r > 0.8);
    // And it is not uniform.
    double lo = 255.0, hi = 0.0;
    for (const double v : on_screen) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    CHECK(hi - lo > 100.0);
}

namespace {

// A client that connected to `port` and trickles a byte of a request line
// now and then, never finishing it (a slow or hostile client).
int open_trickling_client(int port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    REQUIRE(fd >= 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    REQUIRE(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0);
    REQUIRE(::send(fd, "G", 1, MSG_NOSIGNAL) == 1);
    return fd;
}

int status_of(const httplib::Result& result) {
    return result ? result->status : -1;
}

} // namespace

TEST_CASE("cli: the preview needs its token, refuses other origins and hosts, and slow clients "
          "neither starve it nor hold up the exit") {
    Scratch s;
    const fs::path exr = s.dir / "out.exr";
    Child child({"render", kScene, "--width", "16", "--height", "16", "--spp", kManySamples,
                 "--quiet", "--out", exr.string(), "--preview", "0"},
                s);
    const Preview preview = preview_of(child);
    wait_for_spp(preview, 1);

    httplib::Client client("127.0.0.1", preview.port);
    client.set_connection_timeout(5);
    client.set_read_timeout(5);
    // Without the token: nothing, and no stop.
    CHECK(status_of(client.Get("/status.json")) == 403);
    CHECK(status_of(client.Get("/")) == 403);
    CHECK(status_of(client.Post("/stop")) == 403);
    // A page of another origin, and a name rebound to 127.0.0.1.
    CHECK(status_of(client.Post((preview.base + "stop").c_str(),
                                {{"Origin", "http://evil.example"}}, "", "text/plain")) == 403);
    CHECK(status_of(client.Get((preview.base + "status.json").c_str(),
                               {{"Host", "evil.example:" + std::to_string(preview.port)}})) == 403);
    CHECK(get(preview, "status.json").find("\"state\": \"rendering\"") != std::string::npos);

    // Eight clients that trickle bytes: the status is still served.
    std::vector<int> slow;
    for (int i = 0; i < 8; ++i)
        slow.push_back(open_trickling_client(preview.port));
    std::atomic<bool> trickling{true};
    std::thread trickle([&] {
        while (trickling) {
            for (const int fd : slow)
                ::send(fd, "E", 1, MSG_NOSIGNAL); // fails once the server dropped it
            std::this_thread::sleep_for(std::chrono::milliseconds(300));
        }
    });
    const auto before = std::chrono::steady_clock::now();
    CHECK(status_of(client.Get((preview.base + "status.json").c_str())) == 200);
    // The page's own stop (same origin) ends the render, and the exit does
    // not wait for the trickling clients.
    CHECK(status_of(client.Post((preview.base + "stop").c_str(),
                                {{"Origin", "http://127.0.0.1:" + std::to_string(preview.port)}},
                                "", "text/plain")) == 200);
    const int status = child.wait();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
    trickling = false;
    trickle.join();
    for (const int fd : slow)
        ::close(fd);
    INFO("stderr: " << child.err());
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 130);
    CHECK(seconds < 10.0);
}

TEST_CASE("cli: a preview port in use is a one-line error before any work") {
    Scratch s;
    // Another server, listening on a free port.
    const int other = ::socket(AF_INET, SOCK_STREAM, 0);
    REQUIRE(other >= 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    REQUIRE(::bind(other, reinterpret_cast<sockaddr*>(&address), length) == 0);
    REQUIRE(::listen(other, 1) == 0);
    REQUIRE(::getsockname(other, reinterpret_cast<sockaddr*>(&address), &length) == 0);
    const int port = ntohs(address.sin_port);
    const fs::path out = s.dir / "never.exr";
    const Run run = wavepath("render " + kHexroom + " --width 8 --height 8 --preview " +
                                 std::to_string(port) + " --out '" + out.string() + "'",
                             s);
    check_one_line_error(run, "cannot serve the preview on 127.0.0.1:" + std::to_string(port));
    CHECK(run.err.find("kernels built") == std::string::npos);
    CHECK(!fs::exists(out));
    ::close(other);
}

TEST_CASE("cli: an IPv6 preview address is printed in brackets") {
    Scratch s;
    const Run run =
        wavepath("render " + kHexroom + " --width 8 --height 8 --spp 1 --quiet" +
                     " --preview 0 --preview-bind ::1 --out '" + (s.dir / "x.exr").string() + "'",
                 s);
    if (run.exit_code != 0 && run.err.find("cannot serve the preview") != std::string::npos) {
        WARN("skipped: no IPv6 loopback here: " << run.err);
        return;
    }
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == 0);
    CHECK(
        std::regex_search(run.err, std::regex("preview at http://\\[::1\\]:[0-9]+/[0-9a-f]{32}/")));
}
