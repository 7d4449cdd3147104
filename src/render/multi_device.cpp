#include "render/multi_device.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <iostream>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "cl/context.hpp"
#include "cl/error.hpp"

namespace wp {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// What the test hook throws: an error as a lost device gives, mid-chunk.
class InjectedFailure : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

void add_stats(RenderStats& total, const RenderStats& part) {
    total.camera_rays += part.camera_rays;
    total.bounce_rays += part.bounce_rays;
    total.shadow_rays += part.shadow_rays;
    total.iterations += part.iterations;
    total.capped_paths += part.capped_paths;
    total.nonfinite_samples += part.nonfinite_samples;
    total.queue_lengths.insert(total.queue_lengths.end(), part.queue_lengths.begin(),
                               part.queue_lengths.end());
    if (total.rays_per_bounce.size() < part.rays_per_bounce.size())
        total.rays_per_bounce.resize(part.rays_per_bounce.size(), 0);
    for (std::size_t i = 0; i < part.rays_per_bounce.size(); ++i)
        total.rays_per_bounce[i] += part.rays_per_bounce[i];
    total.host_seconds += part.host_seconds;
}

} // namespace

std::string exception_text(const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const cl::Error& e) {
        return describe_cl_error(e);
    } catch (const std::exception& e) {
        return e.what();
    } catch (...) {
        return "unknown error";
    }
}

struct MultiDeviceRenderer::Device {
    DeviceInfo info;
    std::unique_ptr<DeviceContext> context;
    std::unique_ptr<WavefrontIntegrator> integrator;
    Profiler profiler;
    Film film; // samples of the current render() call
    bool film_has_samples = false;
    DeviceShare share;
    std::exception_ptr failure; // set once it has failed; it takes no more chunks
    std::optional<std::uint32_t> fail_after_chunks;

    // This call, read by the rendering thread for progress.
    std::atomic<double> samples_done{0.0}; // per pixel, completed chunks
    std::atomic<double> samples_partial{0.0};
    double call_busy_seconds = 0.0;
    double call_seconds = 0.0; // from the call's start until it stopped taking chunks
};

// Signals the rendering thread that a device made progress or stopped.
struct MultiDeviceRenderer::Wakeup {
    std::mutex mutex;
    std::condition_variable changed;
    std::uint32_t running = 0;
};

MultiDeviceRenderer::MultiDeviceRenderer(const std::vector<DeviceInfo>& devices, const Scene& scene,
                                         IntegratorOptions options, bool profiling)
    : MultiDeviceRenderer(devices, prepare_scene(scene, options), profiling) {}

MultiDeviceRenderer::MultiDeviceRenderer(const std::vector<DeviceInfo>& devices,
                                         const PreparedScene& scene, bool profiling)
    : width_(scene.width), height_(scene.height), wakeup_(std::make_unique<Wakeup>()) {
    if (devices.empty())
        throw std::invalid_argument("MultiDeviceRenderer: no device");
    report_ = [](const std::string& line) { std::cerr << "wavepath: warning: " << line << "\n"; };
    for (const DeviceInfo& info : devices) {
        auto device = std::make_unique<Device>();
        device->info = info;
        device->share.name = info.name;
        device->share.index = info.index_string();
        devices_.push_back(std::move(device));
    }
    // Programs build in parallel: on PoCL each build takes seconds.
    std::vector<std::thread> builders;
    for (auto& device : devices_)
        builders.emplace_back([&, d = device.get()] {
            try {
                d->context = std::make_unique<DeviceContext>(d->info, profiling);
                d->integrator = std::make_unique<WavefrontIntegrator>(*d->context, scene);
                if (profiling)
                    d->integrator->set_profiler(&d->profiler);
            } catch (...) {
                d->failure = std::current_exception();
            }
        });
    for (std::thread& builder : builders)
        builder.join();

    std::exception_ptr first_failure;
    for (auto& device : devices_) {
        if (!device->failure)
            continue;
        if (!first_failure)
            first_failure = device->failure;
        device->share.error = exception_text(device->failure);
    }
    if (device_count() == 0)
        std::rethrow_exception(first_failure);
    for (auto& device : devices_)
        if (device->failure)
            report_("device " + device->share.index + " (" + device->share.name +
                    ") failed: " + device->share.error + "; rendering on the others");
}

MultiDeviceRenderer::~MultiDeviceRenderer() {
    try {
        finish();
    } catch (...) {
        // Nothing to report to from a destructor; the peers end with the process.
    }
}

void MultiDeviceRenderer::set_peers(std::unique_ptr<RenderPeers> peers) {
    peers_ = std::move(peers);
}

void MultiDeviceRenderer::finish() {
    if (!peers_)
        return;
    std::unique_ptr<RenderPeers> peers = std::move(peers_);
    peer_shares_ = peers->finish(peer_stats_);
}

void MultiDeviceRenderer::fail_after_chunks(std::size_t device, std::uint32_t chunks) {
    devices_.at(device)->fail_after_chunks = chunks;
}

std::uint32_t MultiDeviceRenderer::device_count() const {
    std::uint32_t count = peers_ ? peers_->device_count() : 0;
    for (const auto& device : devices_)
        count += device->failure ? 0 : 1;
    return count;
}

std::uint32_t MultiDeviceRenderer::samples_per_call(std::uint32_t one_device) const {
    // Four chunks' worth per device: the chunks then shrink from a quarter
    // of the call down to one sample, and the last one is short.
    const std::uint32_t devices = device_count();
    return devices <= 1 ? one_device : one_device * 4 * devices;
}

void MultiDeviceRenderer::render(std::uint32_t first_sample, std::uint32_t count, Film& film,
                                 const std::function<void(double)>& on_progress) {
    if (devices_.size() == 1 && !peers_ && !devices_[0]->failure &&
        !devices_[0]->fail_after_chunks) {
        // One device: straight into the caller's film, as WavefrontIntegrator
        // alone would (the same image bit for bit, and no film of its own);
        // if it fails, the render fails, so no chunk needs to be redone.
        Device& device = *devices_[0];
        const auto start = Clock::now();
        device.integrator->render(first_sample, count, film, on_progress);
        const double seconds = seconds_since(start);
        device.share.busy_seconds += seconds;
        device.share.chunks += 1;
        device.share.samples += static_cast<std::uint64_t>(width_) * height_ * count;
        render_seconds_ += seconds;
        return;
    }
    ChunkQueue queue(first_sample, count, device_count());
    run(queue, peers_ ? &queue : nullptr, film, on_progress);
}

void MultiDeviceRenderer::render_from(ChunkSource& source, Film& film,
                                      const std::function<void(double)>& on_progress) {
    run(source, nullptr, film, on_progress);
}

void MultiDeviceRenderer::fail(Device& device, std::exception_ptr error,
                               const std::string& while_doing) {
    device.failure = error;
    device.share.error = exception_text(error);
    static std::mutex reporting; // devices fail on their own threads
    std::lock_guard lock(reporting);
    if (devices_.size() > 1 || peers_)
        report_("device " + device.share.index + " (" + device.share.name + ") failed" +
                while_doing + ": " + device.share.error + "; its work goes to the other devices");
}

void MultiDeviceRenderer::run_device(Device& device, ChunkSource& source) {
    const auto start = Clock::now();
    const double pixels = static_cast<double>(width_) * static_cast<double>(height_);
    Wakeup& wakeup = *wakeup_;
    auto notify = [&] { wakeup.changed.notify_all(); };
    for (;;) {
        std::optional<SampleRange> range;
        try {
            range = source.take();
        } catch (...) {
            fail(device, std::current_exception(), " asking for work");
            break;
        }
        if (!range)
            break;
        const auto chunk_start = Clock::now();
        try {
            // A film per chunk: a device that fails mid-chunk leaves
            // nothing of it behind, so the chunk can be rendered again.
            Film chunk(width_, height_);
            const bool inject =
                device.fail_after_chunks && device.share.chunks >= *device.fail_after_chunks;
            const double count = range->count;
            device.integrator->render(range->first, range->count, chunk, [&](double spp) {
                device.samples_partial.store(spp);
                notify();
                if (inject && spp >= 0.75 * count)
                    throw InjectedFailure("device lost (test hook: made to fail after " +
                                          std::to_string(*device.fail_after_chunks) + " chunks)");
            });
            if (inject) // the chunk ended before the hook fired
                throw InjectedFailure("device lost (test hook)");
            if (!device.film_has_samples)
                device.film = std::move(chunk);
            else
                device.film.merge(chunk);
        } catch (...) {
            device.samples_partial.store(0.0);
            device.call_busy_seconds += seconds_since(chunk_start);
            source.give_back(*range);
            fail(device, std::current_exception(),
                 " on samples " + std::to_string(range->first) + "-" +
                     std::to_string(range->first + range->count - 1));
            break;
        }
        const double busy = seconds_since(chunk_start);
        device.call_busy_seconds += busy;
        device.film_has_samples = true;
        device.share.chunks += 1;
        device.share.samples += static_cast<std::uint64_t>(pixels) * range->count;
        device.samples_partial.store(0.0);
        device.samples_done.store(device.samples_done.load() + range->count);
        source.complete(*range);
        notify();
    }
    device.call_seconds = seconds_since(start);
    {
        std::lock_guard lock(wakeup.mutex);
        --wakeup.running;
    }
    notify();
}

void MultiDeviceRenderer::run(ChunkSource& source, ChunkQueue* for_peers, Film& film,
                              const std::function<void(double)>& on_progress) {
    const auto start = Clock::now();
    std::vector<Device*> working;
    for (auto& device : devices_)
        if (!device->failure)
            working.push_back(device.get());
    if (working.empty() && !peers_)
        throw std::runtime_error("every device has failed");

    Wakeup& wakeup = *wakeup_;
    wakeup.running = static_cast<std::uint32_t>(working.size());
    std::vector<std::thread> threads;
    for (Device* device : working) {
        device->samples_done = 0.0;
        device->samples_partial = 0.0;
        device->call_busy_seconds = 0.0;
        threads.emplace_back([this, device, &source] { run_device(*device, source); });
    }

    // This thread reports progress and, on rank 0 of an MPI job, serves the
    // other ranks; it polls often when there are peers, as they wait on it.
    const auto poll = peers_ ? std::chrono::milliseconds(1) : std::chrono::milliseconds(100);
    bool peers_done = !peers_;
    std::exception_ptr abandoned; // a peer's failure: the render cannot go on
    for (;;) {
        bool local_done = false;
        {
            std::unique_lock lock(wakeup.mutex);
            wakeup.changed.wait_for(lock, poll);
            local_done = wakeup.running == 0;
        }
        try {
            if (peers_ && !peers_done)
                peers_done = peers_->serve(*for_peers);
            if (on_progress) {
                double done = peers_ ? peers_->samples_done() : 0.0;
                for (Device* device : working)
                    done += device->samples_done.load() + device->samples_partial.load();
                on_progress(done);
            }
        } catch (...) {
            abandoned = std::current_exception();
            source.cancel(); // the devices stop after their current chunks
            peers_done = true;
        }
        if (local_done && peers_done)
            break;
    }
    for (std::thread& thread : threads)
        thread.join();
    if (abandoned)
        std::rethrow_exception(abandoned);

    const double call_seconds = seconds_since(start);
    for (Device* device : working) {
        device->share.busy_seconds += device->call_busy_seconds;
        device->share.idle_seconds +=
            std::max(0.0, (device->failure ? device->call_seconds : call_seconds) -
                              device->call_busy_seconds);
    }
    render_seconds_ += call_seconds;

    if (source.samples_given_back() > 0) {
        // Every device failed with work left over.
        std::exception_ptr last;
        std::string errors;
        for (const auto& device : devices_) {
            last = device->failure ? device->failure : last;
            errors += (errors.empty() ? "" : "; ") + device->share.index + " (" +
                      device->share.name + "): " + device->share.error;
        }
        if (devices_.size() == 1 && !peers_)
            std::rethrow_exception(last); // as a one-device render would fail
        throw std::runtime_error("every device failed: " + errors);
    }

    // Fixed order: the devices in list order, then the peers in rank order.
    for (auto& device : devices_) {
        if (!device->film_has_samples)
            continue;
        film.merge(device->film);
        device->film = Film();
        device->film_has_samples = false;
    }
    if (peers_)
        peers_->merge_into(film);
}

std::vector<DeviceShare> MultiDeviceRenderer::shares() const {
    std::vector<DeviceShare> out;
    for (const auto& device : devices_)
        out.push_back(device->share);
    out.insert(out.end(), peer_shares_.begin(), peer_shares_.end());
    return out;
}

RenderStats MultiDeviceRenderer::stats() const {
    RenderStats total = peer_stats_;
    for (const auto& device : devices_)
        if (device->integrator)
            add_stats(total, device->integrator->stats());
    total.render_seconds = render_seconds_;
    return total;
}

RenderStats MultiDeviceRenderer::device_stats(std::size_t device) const {
    const Device& d = *devices_.at(device);
    return d.integrator ? d.integrator->stats() : RenderStats{};
}

const WavefrontIntegrator& MultiDeviceRenderer::integrator() const {
    for (const auto& device : devices_)
        if (!device->failure)
            return *device->integrator;
    for (const auto& device : devices_)
        if (device->integrator)
            return *device->integrator;
    throw std::logic_error("MultiDeviceRenderer: no integrator");
}

const WavefrontIntegrator* MultiDeviceRenderer::integrator(std::size_t device) const {
    const Device& d = *devices_.at(device);
    return d.failure ? nullptr : d.integrator.get();
}

const Profiler& MultiDeviceRenderer::profiler(std::size_t device) const {
    return devices_.at(device)->profiler;
}

std::string MultiDeviceRenderer::describe() const {
    std::string text;
    for (const auto& device : devices_)
        text += (text.empty() ? "" : " + ") + device->share.name + " (" + device->share.index + ")";
    return peers_ ? text + " + " + peers_->describe() : text;
}

} // namespace wp
