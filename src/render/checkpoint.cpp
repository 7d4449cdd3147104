#include "render/checkpoint.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string_view>
#include <tuple>
#include <type_traits>

#include "cl/program.hpp"
#include "cl/program_cache.hpp"
#include "util/file.hpp"

#ifndef WAVEPATH_VERSION
#error "WAVEPATH_VERSION must be defined by the build (CMakeLists.txt)"
#endif

namespace wp {

namespace {

constexpr char kMagic[8] = {'W', 'P', 'C', 'H', 'K', 'P', 'T', '\n'};
// Strings longer than this are damage, not options: refused before any
// allocation that a corrupted length could make huge.
constexpr std::uint32_t kMaxTextBytes = 1u << 20;

std::string hex(std::uint64_t x) {
    static const char digits[] = "0123456789abcdef";
    std::string s(16, '0');
    for (int i = 15; i >= 0; --i, x >>= 4)
        s[static_cast<std::size_t>(i)] = digits[x & 15u];
    return s;
}

std::string size_text(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

// Little-endian writing, whatever the host's byte order.
class Writer {
  public:
    void u32(std::uint32_t x) { bytes(x, 4); }
    void u64(std::uint64_t x) { bytes(x, 8); }
    void f64(double x) { u64(std::bit_cast<std::uint64_t>(x)); }
    void text(const std::string& s) {
        u32(static_cast<std::uint32_t>(s.size()));
        out.insert(out.end(), s.begin(), s.end());
    }
    void raw(const char* data, std::size_t n) { out.insert(out.end(), data, data + n); }
    std::vector<unsigned char> out;

  private:
    void bytes(std::uint64_t x, int n) {
        for (int i = 0; i < n; ++i)
            out.push_back(static_cast<unsigned char>(x >> (8 * i)));
    }
};

// Reading the same, with every read bounds-checked: a truncated file is an
// error naming where it ends, never a read past the buffer.
class Reader {
  public:
    Reader(const std::vector<unsigned char>& data, const std::string& path)
        : data_(data), path_(path) {}

    [[noreturn]] void fail(const std::string& reason) const {
        throw CheckpointError("cannot resume from '" + path_ + "': " + reason);
    }
    void need(std::size_t n, const char* what) const {
        if (data_.size() - pos_ < n)
            fail("truncated: it ends inside its " + std::string(what) + " (" +
                 std::to_string(data_.size()) + " bytes)");
    }
    std::uint64_t bytes(int n, const char* what) {
        need(static_cast<std::size_t>(n), what);
        std::uint64_t x = 0;
        for (int i = 0; i < n; ++i)
            x |= static_cast<std::uint64_t>(data_[pos_ + static_cast<std::size_t>(i)]) << (8 * i);
        pos_ += static_cast<std::size_t>(n);
        return x;
    }
    std::uint32_t u32(const char* what) { return static_cast<std::uint32_t>(bytes(4, what)); }
    std::uint64_t u64(const char* what) { return bytes(8, what); }
    double f64(const char* what) { return std::bit_cast<double>(u64(what)); }
    std::string text(const char* what) {
        const std::uint32_t n = u32(what);
        if (n > kMaxTextBytes)
            fail("damaged: its " + std::string(what) + " claims " + std::to_string(n) + " bytes");
        need(n, what);
        std::string s(reinterpret_cast<const char*>(data_.data() + pos_), n);
        pos_ += n;
        return s;
    }
    std::size_t position() const { return pos_; }

  private:
    const std::vector<unsigned char>& data_;
    const std::string& path_;
    std::size_t pos_ = 0;
};

// Hashes values as their bytes, one field at a time (never a struct with
// padding in it).
class Hasher {
  public:
    void f64(double x) { u64(std::bit_cast<std::uint64_t>(x)); }
    void u64(std::uint64_t x) { state = fnv1a64_bytes(&x, sizeof x, state); }
    void vec(const glm::dvec3& v) {
        f64(v.x);
        f64(v.y);
        f64(v.z);
    }
    // A material field (Material::rendered_fields).
    void field(double x) { f64(x); }
    void field(const glm::dvec3& v) { vec(v); }
    void field(const glm::dmat3& m) {
        for (int c = 0; c < 3; ++c)
            vec(m[c]);
    }
    template <typename E>
    requires std::is_enum_v<E>
    void field(E e) { u64(static_cast<std::uint64_t>(e)); }
    std::uint64_t state = kFnvOffset;
};

// "seed=3, now seed=4": the first space-separated word in which two option
// texts differ, or the extra words of the longer one.
std::string first_difference(const std::string& was, const std::string& now) {
    auto words = [](const std::string& s) {
        std::vector<std::string> out;
        std::size_t start = 0;
        while (start <= s.size()) {
            const std::size_t end = std::min(s.find(' ', start), s.size());
            out.push_back(s.substr(start, end - start));
            start = end + 1;
        }
        return out;
    };
    auto rest = [](const std::vector<std::string>& w, std::size_t from) {
        std::string out;
        for (std::size_t i = from; i < w.size(); ++i)
            out += (out.empty() ? "" : " ") + w[i];
        return out.empty() ? std::string("(nothing)") : out;
    };
    const std::vector<std::string> a = words(was), b = words(now);
    for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
        if (i >= a.size() || i >= b.size())
            return rest(a, i) + ", now " + rest(b, i);
        if (a[i] != b[i])
            return a[i] + ", now " + b[i];
    }
    return "none";
}

} // namespace

std::uint64_t scene_content_hash(const Scene& scene) {
    Hasher h;
    const Camera& c = scene.camera;
    h.vec(c.eye);
    h.vec(c.look_at);
    h.vec(c.up);
    h.f64(c.vertical_fov_degrees);
    h.f64(c.aperture_radius);
    h.f64(c.focus_distance);
    h.u64(static_cast<std::uint64_t>(c.filter));
    h.f64(c.filter_radius);
    h.f64(c.filter_stddev);
    h.u64(scene.materials.size());
    // Every value that changes how a material renders: a changed roughness or
    // index of refraction must not resume silently.
    for (const Material& m : scene.materials)
        std::apply([&](const auto&... field) { (h.field(field), ...); }, m.rendered_fields());
    auto triangles = [&](const TriangleList& list) {
        h.u64(list.size());
        for (const Triangle& t : list) {
            for (const glm::dvec3& v : t.v)
                h.vec(v);
            h.u64(t.material);
            h.u64(t.has_normals ? 1 : 0);
            if (t.has_normals)
                for (const glm::dvec3& n : t.normals)
                    h.vec(n);
            h.u64(t.has_uvs ? 1 : 0);
            if (t.has_uvs)
                for (const glm::dvec2& uv : t.uvs)
                    h.vec(glm::dvec3(uv, 0.0));
        }
    };
    triangles(scene.triangles);
    // A texture by its values, texels included: a changed image file under
    // the same name must not resume silently.
    h.u64(scene.textures.size());
    for (const Texture& t : scene.textures) {
        h.u64(static_cast<std::uint64_t>(t.kind));
        h.vec(t.to_u);
        h.vec(t.to_v);
        h.vec(t.color0);
        h.vec(t.color1);
        h.u64(static_cast<std::uint64_t>(t.filter));
        h.u64(static_cast<std::uint64_t>(t.wrap));
        if (t.image) {
            h.u64(t.image->width);
            h.u64(t.image->height);
            h.u64(static_cast<std::uint64_t>(t.image->encoding));
            h.state = fnv1a64_bytes(t.image->texels.data(), t.image->bytes(), h.state);
        }
    }
    h.u64(scene.spheres.size());
    for (const Sphere& s : scene.spheres) {
        h.vec(s.center);
        h.f64(s.radius);
        h.u64(s.material);
    }
    // Only when there are any, so that the hash of a scene without emitters
    // (every checkpoint written before they existed) is unchanged.
    if (!scene.emitters.empty()) {
        h.u64(scene.emitters.size());
        for (const Emitter& e : scene.emitters) {
            std::apply([&](const auto&... field) { (h.field(field), ...); }, e.rendered_fields());
            if (e.image) { // an envmap's, by its values as a texture's
                h.u64(e.image->width);
                h.u64(e.image->height);
                h.u64(static_cast<std::uint64_t>(e.image->encoding));
                h.state = fnv1a64_bytes(e.image->texels.data(), e.image->bytes(), h.state);
            }
        }
    }
    // Likewise only when there are any: shape groups by their triangles,
    // instances by their group and map.
    if (!scene.shape_groups.empty() || !scene.instances.empty()) {
        h.u64(scene.shape_groups.size());
        for (const ShapeGroup& g : scene.shape_groups)
            triangles(g.triangles);
        h.u64(scene.instances.size());
        for (const Instance& instance : scene.instances) {
            h.u64(instance.group);
            for (int column = 0; column < 4; ++column)
                h.vec(glm::dvec3(instance.to_world[column]));
        }
    }
    return h.state;
}

std::string checkpoint_options(const IntegratorOptions& options, const std::string& build_options) {
    return "seed=" + std::to_string(options.seed) +
           " max-depth=" + std::to_string(options.max_depth) +
           " estimator=" + describe_estimator(options) +
           " general=" + std::to_string(options.general_kernels) +
           " traversal=" + to_string(options.traversal) +
           " terminator-fix=" + std::to_string(options.shadow_terminator_fix) + " regeneration=" +
           (options.regeneration ? std::to_string(*options.regeneration) : std::string("auto")) +
           " pool=" + std::to_string(options.pool_size) + " build=" + build_options;
}

std::string renderer_version() {
    static const std::string version =
        std::string("wavepath ") + WAVEPATH_VERSION + ", kernels " +
        hex(fnv1a64(expand_includes(wavefront_program_source(), "wavefront.cl")));
    return version;
}

CheckpointIdentity checkpoint_identity(const Scene& scene, const IntegratorOptions& options,
                                       const std::string& build_options) {
    return checkpoint_identity(scene_content_hash(scene), scene, options, build_options);
}

CheckpointIdentity checkpoint_identity(std::uint64_t scene_hash, const Scene& scene,
                                       const IntegratorOptions& options,
                                       const std::string& build_options) {
    return {scene_hash, scene.camera.width, scene.camera.height,
            checkpoint_options(options, build_options), renderer_version()};
}

std::vector<unsigned char> encode_checkpoint(const CheckpointIdentity& id,
                                             std::uint32_t samples_per_pixel, const Film& film) {
    const FilmSums sums = film.sums();
    Writer w;
    w.raw(kMagic, sizeof kMagic);
    w.u32(kCheckpointFormat);
    w.u32(static_cast<std::uint32_t>(id.width));
    w.u32(static_cast<std::uint32_t>(id.height));
    w.u32(samples_per_pixel);
    w.u64(id.scene_hash);
    w.text(id.version);
    w.text(id.options);
    for (const std::vector<double>* a : {&sums.sum, &sums.sum_squares, &sums.odd_sum})
        for (double x : *a)
            w.f64(x);
    for (const std::vector<std::uint64_t>* a : {&sums.count, &sums.odd_count})
        for (std::uint64_t x : *a)
            w.u64(x);
    for (double x : sums.aov_sum) // a render with AOVs: 7 more a pixel; else none
        w.f64(x);
    w.u64(fnv1a64_bytes(w.out.data(), w.out.size()));
    return std::move(w.out);
}

FilmCheckpoint decode_checkpoint(const std::vector<unsigned char>& bytes, const std::string& path) {
    Reader r(bytes, path);
    if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        r.fail("not a wavepath checkpoint (no \"WPCHKPT\" at its start)");
    r.bytes(sizeof kMagic, "magic");
    const std::uint32_t format = r.u32("format version");
    if (format != kCheckpointFormat)
        r.fail("it has checkpoint format " + std::to_string(format) + "; this wavepath (" +
               renderer_version() + ") reads format " + std::to_string(kCheckpointFormat));
    FilmCheckpoint c;
    const std::uint32_t width = r.u32("header"), height = r.u32("header");
    c.samples_per_pixel = r.u32("header");
    c.identity.scene_hash = r.u64("header");
    c.identity.version = r.text("version");
    c.identity.options = r.text("options");
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
        r.fail("damaged: its resolution " + std::to_string(width) + "x" + std::to_string(height) +
               " is impossible");
    c.identity.width = static_cast<int>(width);
    c.identity.height = static_cast<int>(height);

    // The rest has a known size: check it before reading (or allocating) it.
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    // A render with AOVs (--aov) saves their sums too, 7 doubles a pixel after
    // the counts (Film::sums); which of the two it is, the size says, and the
    // checksum and the options (its kernels' -D WP_AOV=1) back it up.
    std::size_t expected = r.position() + pixels * (9 + 2) * 8 + 8;
    const std::size_t aov_bytes = pixels * 7 * 8;
    const bool aovs = bytes.size() == expected + aov_bytes;
    if (aovs)
        expected += aov_bytes;
    if (bytes.size() < expected)
        r.fail("truncated: " + std::to_string(bytes.size()) + " of its " +
               std::to_string(expected) + " bytes");
    if (bytes.size() > expected)
        r.fail("damaged: " + std::to_string(bytes.size() - expected) + " bytes past its end");
    const std::uint64_t checksum = fnv1a64_bytes(bytes.data(), bytes.size() - 8);
    FilmSums sums;
    for (std::vector<double>* a : {&sums.sum, &sums.sum_squares, &sums.odd_sum}) {
        a->resize(pixels * 3);
        for (double& x : *a)
            x = r.f64("film");
    }
    for (std::vector<std::uint64_t>* a : {&sums.count, &sums.odd_count}) {
        a->resize(pixels);
        for (std::uint64_t& x : *a)
            x = r.u64("film");
    }
    if (aovs) {
        sums.aov_sum.resize(pixels * 7);
        for (double& x : sums.aov_sum)
            x = r.f64("AOVs");
    }
    if (r.u64("checksum") != checksum)
        r.fail("damaged: its checksum does not match its contents");
    // The kernels drop non-finite samples (counted as NaN/Inf in the summary),
    // so a saved film's sums are finite: a NaN here is a crafted or damaged
    // file whose checksum was made to match, and it would resume into a NaN
    // image while the summary reported no NaN sample.
    const char* const sum_names[] = {"sum", "sum of squares", "odd-sample sum"};
    int which = 0;
    for (const std::vector<double>* a : {&sums.sum, &sums.sum_squares, &sums.odd_sum}) {
        for (std::size_t i = 0; i < a->size(); ++i)
            if (!std::isfinite((*a)[i]))
                r.fail("damaged: pixel " + std::to_string(i / 3) + "'s " + sum_names[which] +
                       " is not finite (" + std::to_string((*a)[i]) + ")");
        ++which;
    }
    for (std::size_t i = 0; i < sums.aov_sum.size(); ++i)
        if (!std::isfinite(sums.aov_sum[i]))
            r.fail("damaged: pixel " + std::to_string(i / 7) + "'s AOV sum is not finite (" +
                   std::to_string(sums.aov_sum[i]) + ")");
    // Written only between render() calls, where every pixel holds every
    // sample index below samples_per_pixel, half of them odd.
    for (std::size_t p = 0; p < pixels; ++p)
        if (sums.count[p] != c.samples_per_pixel || sums.odd_count[p] != c.samples_per_pixel / 2)
            r.fail("damaged: pixel " + std::to_string(p) + " holds " +
                   std::to_string(sums.count[p]) + " samples, not the header's " +
                   std::to_string(c.samples_per_pixel));
    c.film = Film(c.identity.width, c.identity.height, std::move(sums));
    return c;
}

void save_checkpoint(const std::filesystem::path& path, const CheckpointIdentity& identity,
                     std::uint32_t samples_per_pixel, const Film& film) {
    const std::vector<unsigned char> bytes = encode_checkpoint(identity, samples_per_pixel, film);
    write_bytes_atomically(path, bytes.data(), bytes.size());
}

FilmCheckpoint load_checkpoint(const std::filesystem::path& path,
                               const CheckpointIdentity& expected) {
    const std::string name = path.string();
    auto fail = [&name](const std::string& reason) -> void {
        throw CheckpointError("cannot resume from '" + name + "': " + reason);
    };
    std::vector<unsigned char> bytes;
    try {
        bytes = read_file_bytes(path);
    } catch (const FileError& e) {
        fail(e.reason());
    }
    FilmCheckpoint c = decode_checkpoint(bytes, name);
    const CheckpointIdentity& got = c.identity;
    if (got.version != expected.version)
        fail("it was written by " + got.version + ", and this is " + expected.version);
    if (got.scene_hash != expected.scene_hash)
        fail("it is of another scene (scene hash " + hex(got.scene_hash) + ", this scene's " +
             hex(expected.scene_hash) + ")");
    if (got.width != expected.width || got.height != expected.height)
        fail("it is of a " + size_text(got.width, got.height) + " image, and this render is " +
             size_text(expected.width, expected.height));
    if (got.options != expected.options)
        fail("it was rendered with other options: " +
             first_difference(got.options, expected.options));
    return c;
}

} // namespace wp
