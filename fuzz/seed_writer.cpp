// Writes the generated part of the fuzzers' seed corpora: small valid files in
// the binary formats, in the variants the readers handle, so that each fuzzer
// starts from inputs that reach deep into its reader rather than from nothing.
//
//   wavepath_fuzz_seeds OUT_DIR     writes OUT_DIR/{exr,pfm,ply}/...
//
// fuzz/make-corpora.sh runs it and adds the repository's own files (scenes/,
// tests/data/, fuzz/seeds/). The EXR seeds cover every compression the Debian
// tinyexr decodes, with half and float channels, an extra alpha channel and a
// string attribute; the PLY seeds every scalar type in both byte orders.
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <tinyexr.h>

#include "image/exr.hpp"
#include "image/pfm.hpp"

namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& bytes) {
    fs::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out)
        throw std::runtime_error("cannot write " + path.string());
}

// A small gradient, so that no channel is constant (constant planes compress to
// almost nothing and would exercise less of the decoders).
wp::Image gradient(int width, int height) {
    wp::Image img(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float* p = img.pixel(x, y);
            p[0] = 0.25f * static_cast<float>(x);
            p[1] = 0.5f * static_cast<float>(y);
            p[2] = static_cast<float>(x + y) + 0.125f;
        }
    return img;
}

// An EXR with channels B, G, R (and A when asked) of one pixel type and one
// compression, encoded by tinyexr itself.
std::string exr(int compression, int pixel_type, bool alpha) {
    const int width = 5, height = 3;
    const wp::Image img = gradient(width, height);
    const int channels = alpha ? 4 : 3;
    const char* names[4] = {"A", "B", "G", "R"};
    const int first = alpha ? 0 : 1;
    std::vector<std::vector<float>> planes(static_cast<std::size_t>(channels),
                                           std::vector<float>(width * height));
    for (int c = 0; c < channels; ++c)
        for (int i = 0; i < width * height; ++i) {
            const int name = first + c;
            planes[c][i] = name == 0 ? 1.0f : img.rgb[static_cast<std::size_t>(i) * 3 + (3 - name)];
        }
    std::vector<unsigned char*> pointers;
    for (auto& plane : planes)
        pointers.push_back(reinterpret_cast<unsigned char*>(plane.data()));

    EXRImage image;
    InitEXRImage(&image);
    image.num_channels = channels;
    image.width = width;
    image.height = height;
    image.images = pointers.data();
    std::vector<EXRChannelInfo> info(static_cast<std::size_t>(channels));
    std::vector<int> input_types(static_cast<std::size_t>(channels), TINYEXR_PIXELTYPE_FLOAT);
    std::vector<int> stored_types(static_cast<std::size_t>(channels), pixel_type);
    for (int c = 0; c < channels; ++c)
        std::strncpy(info[c].name, names[first + c], sizeof info[c].name - 1);
    EXRHeader header;
    InitEXRHeader(&header);
    header.num_channels = channels;
    header.channels = info.data();
    header.pixel_types = input_types.data();
    header.requested_pixel_types = stored_types.data();
    header.compression_type = compression;

    unsigned char* memory = nullptr;
    const char* err = nullptr;
    const std::size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
    if (size == 0)
        throw std::runtime_error(std::string("tinyexr: ") + (err ? err : "encoding failed"));
    std::string bytes(reinterpret_cast<const char*>(memory), size);
    std::free(memory);
    return bytes;
}

void write_exr_seeds(const fs::path& dir) {
    const std::pair<int, const char*> compressions[] = {{TINYEXR_COMPRESSIONTYPE_NONE, "none"},
                                                        {TINYEXR_COMPRESSIONTYPE_RLE, "rle"},
                                                        {TINYEXR_COMPRESSIONTYPE_ZIPS, "zips"},
                                                        {TINYEXR_COMPRESSIONTYPE_ZIP, "zip"},
                                                        {TINYEXR_COMPRESSIONTYPE_PIZ, "piz"}};
    for (const auto& [compression, name] : compressions) {
        write(dir / ("half-" + std::string(name) + ".exr"),
              exr(compression, TINYEXR_PIXELTYPE_HALF, false));
        write(dir / ("float-" + std::string(name) + ".exr"),
              exr(compression, TINYEXR_PIXELTYPE_FLOAT, false));
    }
    write(dir / "half-rgba-zip.exr",
          exr(TINYEXR_COMPRESSIONTYPE_ZIP, TINYEXR_PIXELTYPE_HALF, true));
    // wavepath's own writer, with the metadata attribute a cut-short render carries.
    wp::Image img = gradient(4, 17); // more than one 16-line ZIP block
    img.metadata.emplace_back("wavepath:spp", "12 of 64 (interrupted)");
    wp::write_exr(dir / "wavepath-metadata.exr", img);
}

void write_pfm_seeds(const fs::path& dir) {
    wp::write_pfm(dir / "little-endian.pfm", gradient(3, 2));
    // The big-endian form: the same header with a positive scale, floats byte-swapped.
    const wp::Image img = gradient(2, 2);
    std::string bytes = "PF\n2 2\n1.0\n";
    for (int y = img.height - 1; y >= 0; --y)
        for (int i = 0; i < img.width * 3; ++i) {
            std::uint32_t bits;
            std::memcpy(&bits, img.pixel(0, y) + i, 4);
            for (int b = 3; b >= 0; --b)
                bytes.push_back(static_cast<char>((bits >> (8 * b)) & 0xffu));
        }
    write(dir / "big-endian.pfm", bytes);
}

// Little-endian scalars into a byte string, reversed for big-endian files.
class Bytes {
  public:
    explicit Bytes(bool big_endian) : big_endian_(big_endian) {}
    template <typename T> void put(T v) {
        std::array<char, sizeof(T)> raw;
        std::memcpy(raw.data(), &v, sizeof(T));
        if (big_endian_)
            for (std::size_t i = sizeof(T); i-- > 0;)
                s_.push_back(raw[i]);
        else
            s_.append(raw.data(), raw.size());
    }
    // One value of the PLY type `type`.
    void put_as(const std::string& type, double v) {
        // Integers go through int64, so that -1 (a strip restart) wraps to
        // 0xffffffff as a writer's unsigned type would store it.
        const auto i = static_cast<std::int64_t>(v);
        if (type == "char")
            put(static_cast<std::int8_t>(i));
        else if (type == "uchar")
            put(static_cast<std::uint8_t>(i));
        else if (type == "short")
            put(static_cast<std::int16_t>(i));
        else if (type == "ushort")
            put(static_cast<std::uint16_t>(i));
        else if (type == "int")
            put(static_cast<std::int32_t>(i));
        else if (type == "uint")
            put(static_cast<std::uint32_t>(i));
        else if (type == "float")
            put(static_cast<float>(v));
        else
            put(v);
    }
    const std::string& str() const { return s_; }

  private:
    bool big_endian_;
    std::string s_;
};

// A square pyramid: four triangles and a quad base, with normals, an extra
// per-vertex property and a skipped element, and a strip element.
std::string binary_ply(bool big_endian, const std::string& coordinate, const std::string& count,
                       const std::string& index) {
    const double positions[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {0.5, 1, 0.5}};
    const int faces[5][4] = {
        {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}, {0, 3, 2, 1}};
    std::string header = std::string("ply\nformat ") +
                         (big_endian ? "binary_big_endian" : "binary_little_endian") +
                         " 1.0\ncomment generated by wavepath_fuzz_seeds\n"
                         "element vertex 5\nproperty " +
                         coordinate + " x\nproperty " + coordinate + " y\nproperty " + coordinate +
                         " z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                         "property uchar red\nelement face 5\nproperty list " +
                         count + " " + index +
                         " vertex_indices\nelement edge 1\nproperty int vertex1\n"
                         "property int vertex2\nelement tristrips 1\nproperty list " +
                         count + " " + index + " vertex_indices\nend_header\n";
    Bytes b(big_endian);
    for (const auto& p : positions) {
        for (double v : p)
            b.put_as(coordinate, v);
        for (double v : p)
            b.put(static_cast<float>(v - 0.5));
        b.put(static_cast<std::uint8_t>(200));
    }
    for (const auto& f : faces) {
        const int n = f[3] < 0 ? 3 : 4;
        b.put_as(count, n);
        for (int k = 0; k < n; ++k)
            b.put_as(index, f[k]);
    }
    b.put(std::int32_t{0});
    b.put(std::int32_t{1});
    const int strip[] = {0, 1, 3, 2, -1, 4, 4, 1};
    b.put_as(count, 8);
    for (int v : strip)
        b.put_as(index, v);
    return header + b.str();
}

void write_ply_seeds(const fs::path& dir) {
    write(dir / "le-float-uchar-int.ply", binary_ply(false, "float", "uchar", "int"));
    write(dir / "be-float-uchar-int.ply", binary_ply(true, "float", "uchar", "int"));
    write(dir / "le-double-ushort-uint.ply", binary_ply(false, "double", "ushort", "uint"));
    write(dir / "be-double-char-short.ply", binary_ply(true, "double", "char", "short"));
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: wavepath_fuzz_seeds OUT_DIR\n";
        return 2;
    }
    try {
        const fs::path out = argv[1];
        for (const char* format : {"exr", "pfm", "ply"})
            fs::create_directories(out / format); // wp's writers need the folder to exist
        write_exr_seeds(out / "exr");
        write_pfm_seeds(out / "pfm");
        write_ply_seeds(out / "ply");
    } catch (const std::exception& e) {
        std::cerr << "wavepath_fuzz_seeds: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
