// Saving a render's film so that an interrupted or long render can go on
// later (`wavepath render --checkpoint FILE`, `--resume FILE`).
//
// A checkpoint holds the film's double sums and counts after a whole number
// of samples per pixel, and what those sums depend on: the scene, the
// resolution, the integrator's options (seed, estimator, build options) and
// the renderer's version. Resuming with any of them changed would mix the
// samples of two different images, so load_checkpoint refuses it with one
// line naming what differs; a damaged or truncated file is refused too.
// Resumed at a render() call boundary of the uninterrupted render, with the
// same device, the film continues with exactly the same sums: the result is
// the uninterrupted render's, bit for bit.
//
// The file (little-endian; format 1):
//
//   offset  bytes  field
//        0      8  magic "WPCHKPT\n"
//        8      4  format version (kCheckpointFormat)
//       12      4  width
//       16      4  height
//       20      4  samples per pixel the film holds
//       24      8  scene hash (scene_content_hash)
//       32      4  n, then n bytes: the renderer version (renderer_version)
//        .      4  m, then m bytes: the options (checkpoint_options)
//        .         per pixel, 3 doubles each: sums, sums of squares, odd-sample sums
//        .         per pixel, 1 uint64 each: sample counts, odd-sample counts
//   end - 8     8  checksum: FNV-1a 64 of every byte before it
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/film.hpp"
#include "render/integrator_options.hpp"
#include "scene/scene.hpp"

namespace wp {

inline constexpr std::uint32_t kCheckpointFormat = 1;

// A checkpoint that cannot be used. what() is one line,
// "cannot resume from '<path>': <reason>".
class CheckpointError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// What a checkpoint's film depends on; resuming needs all of it to match.
struct CheckpointIdentity {
    std::uint64_t scene_hash = 0;
    int width = 0;
    int height = 0;
    std::string options;
    std::string version;
};

struct FilmCheckpoint {
    CheckpointIdentity identity;
    std::uint32_t samples_per_pixel = 0;
    Film film;
};

// FNV-1a 64 of everything in a loaded scene that decides its image except
// the resolution (checked on its own): camera, materials, every triangle
// with its normals, every sphere. Mesh files are covered, as their
// triangles are in the scene; formatting and comments of the file are not.
std::uint64_t scene_content_hash(const Scene& scene);

// The options that decide the samples, as text, e.g. "seed=3 max-depth=1024
// estimator=cosine+nee+area ... build=-D WP_HAS_TRIANGLES=1 ...".
std::string checkpoint_options(const IntegratorOptions& options, const std::string& build_options);

// wavepath's version and a hash of the kernels' source, e.g.
// "wavepath 0.1.0, kernels 0123456789abcdef".
std::string renderer_version();

// The identity of a render of `scene` (at its camera's resolution).
CheckpointIdentity checkpoint_identity(const Scene& scene, const IntegratorOptions& options,
                                       const std::string& build_options);
// The same with the scene's hash given (scene_content_hash, taken before its
// triangles were freed); the rest of `scene` as it is.
CheckpointIdentity checkpoint_identity(std::uint64_t scene_hash, const Scene& scene,
                                       const IntegratorOptions& options,
                                       const std::string& build_options);

// The file's bytes, and back. decode_checkpoint throws CheckpointError
// (naming `path`) for a file that is not a checkpoint, of another format,
// truncated, damaged, or whose counts are not `samples_per_pixel` in every pixel.
std::vector<unsigned char> encode_checkpoint(const CheckpointIdentity& identity,
                                             std::uint32_t samples_per_pixel, const Film& film);
FilmCheckpoint decode_checkpoint(const std::vector<unsigned char>& bytes, const std::string& path);

// Writes the checkpoint atomically (util/file.hpp): a reader or a crash sees
// the old checkpoint or the new one, never half of one.
void save_checkpoint(const std::filesystem::path& path, const CheckpointIdentity& identity,
                     std::uint32_t samples_per_pixel, const Film& film);

// Reads a checkpoint and checks it against the render about to resume from
// it: throws CheckpointError naming the version, scene, resolution or
// options that differ, or why the file cannot be read.
FilmCheckpoint load_checkpoint(const std::filesystem::path& path,
                               const CheckpointIdentity& expected);

} // namespace wp
