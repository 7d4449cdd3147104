// One render on several OpenCL devices at once (and, through RenderPeers, on
// other processes' devices: src/mpi/).
//
// Each device has everything a one-device render has but the prepared scene
// (render/prepared_scene.hpp, made once and uploaded by every device): its
// own context and queue, its programs (built, and cached, for that device), scene buffers,
// path state and film, and a host thread that drives its WavefrontIntegrator.
// The threads take chunks of samples from a ChunkSource (chunk_source.hpp)
// until none are left; at the end of every render() call the devices' films
// are added to the caller's film in device order. Chunks are handed out by
// demand, so the split is not the same from run to run, and the image equals
// a one-device render of the same samples up to the rounding of the sums.
//
// A device whose integrator throws (a build failure, a lost device, out of
// resources) is reported and dropped: the chunk it held is rendered by the
// others, and what it finished before stays in the image (each chunk is
// rendered into a film of its own, added to the device's film only once it
// is complete). Only when every device has failed does render() throw.
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "render/chunk_source.hpp"
#include "render/film.hpp"
#include "render/integrator_options.hpp"
#include "render/profiler.hpp"
#include "render/wavefront.hpp"
#include "scene/scene.hpp"

namespace wp {

// One device's part in a render.
struct DeviceShare {
    std::string name;
    std::string index;         // "P:D" on its machine
    int rank = 0;              // the MPI rank it belongs to (0 without MPI)
    std::string host;          // with MPI: the machine's name
    std::uint64_t samples = 0; // pixel samples rendered: pixels x samples per pixel of its chunks
    std::uint32_t chunks = 0;
    double busy_seconds = 0.0; // rendering chunks
    double idle_seconds = 0.0; // in a render() call without a chunk (waiting for the others)
    std::string error;         // why it stopped, when it failed

    double samples_per_second() const {
        return busy_seconds > 0 ? static_cast<double>(samples) / busy_seconds : 0.0;
    }
};

// The one line an exception from a device (or another rank) says: an OpenCL
// error described (cl/error.hpp), or what().
std::string exception_text(const std::exception_ptr& error);

// Other processes that render chunks of the same image (MPI ranks), served
// from the process that holds the output (rank 0). See src/mpi/.
class RenderPeers {
  public:
    virtual ~RenderPeers() = default;
    // Their devices, for the chunk sizes.
    virtual std::uint32_t device_count() const = 0;
    // Called on the rendering thread, over and over, during a render() call:
    // answers their requests for chunks from `queue`, and receives their
    // films once the queue is empty. True when every peer's film of this
    // call has arrived.
    virtual bool serve(ChunkQueue& queue) = 0;
    // Samples per pixel the peers have finished in this call (progress).
    virtual double samples_done() const = 0;
    // Adds this call's films to `film`, in rank order, and forgets them.
    virtual void merge_into(Film& film) = 0;
    // Tells the peers the render is over; their devices' shares, and their
    // ray and sample counts added to `stats`.
    virtual std::vector<DeviceShare> finish(RenderStats& stats) = 0;
    // "3 devices on 2 other ranks", for the start-up line.
    virtual std::string describe() const = 0;
};

class MultiDeviceRenderer {
  public:
    // Opens every device and builds its programs, in parallel. A device that
    // fails here is reported and left out; when every device fails, the
    // first one's exception is rethrown (for one device: exactly what a
    // one-device render would throw).
    MultiDeviceRenderer(const std::vector<DeviceInfo>& devices, const Scene& scene,
                        IntegratorOptions options, bool profiling = false);
    // The same for a scene already prepared: every device uploads its arrays
    // (the scene is analysed, flattened and its hierarchy built once, however
    // many devices there are; the first constructor prepares it so too).
    MultiDeviceRenderer(const std::vector<DeviceInfo>& devices, const PreparedScene& scene,
                        bool profiling = false);
    ~MultiDeviceRenderer();
    MultiDeviceRenderer(const MultiDeviceRenderer&) = delete;
    MultiDeviceRenderer& operator=(const MultiDeviceRenderer&) = delete;

    // Renders samples [first_sample, first_sample + count) of every pixel
    // into `film`, split among the devices (and peers); as
    // WavefrontIntegrator::render. `on_progress` is called on this thread.
    void render(std::uint32_t first_sample, std::uint32_t count, Film& film,
                const std::function<void(double)>& on_progress = {});
    // Renders the chunks `source` hands out (an MPI rank's, from rank 0).
    void render_from(ChunkSource& source, Film& film,
                     const std::function<void(double)>& on_progress = {});

    // Lets other processes take part (rank 0 of an MPI job).
    void set_peers(std::unique_ptr<RenderPeers> peers);
    // Ends the peers' part and adds their devices to shares(). Idempotent;
    // the destructor calls it too.
    void finish();

    // How many samples per pixel a caller should ask of one render() call
    // for the devices to balance, given what it would ask of one device:
    // enough for a few chunks per device.
    std::uint32_t samples_per_call(std::uint32_t one_device) const;

    // Devices that are (still) rendering, here and at the peers.
    std::uint32_t device_count() const;
    std::size_t local_device_count() const { return devices_.size(); }
    // Every device, the failed ones too: local ones in list order, then the
    // peers' (after finish()).
    std::vector<DeviceShare> shares() const;
    // Summed over the local devices; render_seconds is the wall time of the
    // render() calls.
    RenderStats stats() const;
    // The first working device's integrator (its program, features, pool).
    const WavefrontIntegrator& integrator() const;
    // Per local device (list order): its integrator (null once failed),
    // profiler (with profiling on) and statistics.
    const WavefrontIntegrator* integrator(std::size_t device) const;
    const Profiler& profiler(std::size_t device) const;
    RenderStats device_stats(std::size_t device) const;
    // "name (P:D)", joined by " + ".
    std::string describe() const;

    // Where failures are reported (default: a warning line on stderr).
    void set_failure_reporter(std::function<void(const std::string&)> report) {
        report_ = std::move(report);
    }
    // Test hook: device `device` fails as a lost device would, when it takes
    // a chunk after completing `chunks` of them.
    void fail_after_chunks(std::size_t device, std::uint32_t chunks);

  private:
    struct Device;
    struct Wakeup;
    void run(ChunkSource& source, ChunkQueue* for_peers, Film& film,
             const std::function<void(double)>& on_progress);
    void run_device(Device& device, ChunkSource& source);
    void fail(Device& device, std::exception_ptr error, const std::string& while_doing);

    std::vector<std::unique_ptr<Device>> devices_;
    std::unique_ptr<RenderPeers> peers_;
    std::vector<DeviceShare> peer_shares_;
    RenderStats peer_stats_;
    int width_ = 0;
    int height_ = 0;
    double render_seconds_ = 0.0;
    std::function<void(const std::string&)> report_;
    std::unique_ptr<Wakeup> wakeup_;
};

} // namespace wp
