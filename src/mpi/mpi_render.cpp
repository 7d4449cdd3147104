#include "mpi/mpi_render.hpp"

#include <array>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <vector>

#include <mpi.h>
#include <nlohmann/json.hpp>

#include "cl/device.hpp"
#include "cl/error.hpp"
#include "render/checkpoint.hpp"

namespace wp {
namespace {

enum Tag : int { kStart = 1, kGo, kRequest, kReply, kFilm, kFailed, kBye };
enum ReplyKind : std::uint32_t { kChunk = 0, kDone = 1, kEnd = 2 };

nlohmann::json share_json(const DeviceShare& s) {
    return {{"name", s.name},         {"index", s.index},       {"rank", s.rank},
            {"host", s.host},         {"samples", s.samples},   {"chunks", s.chunks},
            {"busy", s.busy_seconds}, {"idle", s.idle_seconds}, {"error", s.error}};
}

DeviceShare share_from_json(const nlohmann::json& j) {
    DeviceShare s;
    s.name = j.at("name");
    s.index = j.at("index");
    s.rank = j.at("rank");
    s.host = j.at("host");
    s.samples = j.at("samples");
    s.chunks = j.at("chunks");
    s.busy_seconds = j.at("busy");
    s.idle_seconds = j.at("idle");
    s.error = j.at("error");
    return s;
}

void send_film(const MpiJob& job, const Film& film, bool has_samples) {
    std::uint64_t header = has_samples ? 1 : 0;
    MPI_Send(&header, 1, MPI_UINT64_T, 0, kFilm, MPI_COMM_WORLD);
    if (!has_samples)
        return;
    const FilmSums sums = film.sums();
    job.send_doubles(0, kFilm, sums.sum);
    job.send_doubles(0, kFilm, sums.sum_squares);
    job.send_doubles(0, kFilm, sums.odd_sum);
    job.send_counts(0, kFilm, sums.count);
    job.send_counts(0, kFilm, sums.odd_count);
    job.send_doubles(0, kFilm, sums.aov_sum); // empty without AOVs
}

// A rank's chunks come from rank 0, one request per chunk.
class RemoteChunkSource : public ChunkSource {
  public:
    explicit RemoteChunkSource(const MpiJob& job) : job_(job) {}
    bool ended() const { return ended_; }

  protected:
    std::optional<SampleRange> next_range(std::uint64_t completed) override {
        MPI_Send(&completed, 1, MPI_UINT64_T, 0, kRequest, MPI_COMM_WORLD);
        std::array<std::uint32_t, 3> reply{};
        MPI_Recv(reply.data(), 3, MPI_UINT32_T, 0, kReply, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (reply[0] == kChunk)
            return SampleRange{reply[1], reply[2]};
        if (reply[0] == kEnd)
            ended_ = true;
        return std::nullopt;
    }

  private:
    const MpiJob& job_;
    bool ended_ = false; // written and read by one thread at a time (the source's lock)
};

// Rank 0's view of the other ranks.
class MpiPeers : public RenderPeers {
  public:
    MpiPeers(MpiJob& job, std::vector<std::uint32_t> devices, std::vector<std::string> hosts,
             int width, int height)
        : job_(job), devices_(std::move(devices)), hosts_(std::move(hosts)), width_(width),
          height_(height), films_(job.size()), film_arrived_(job.size(), false),
          done_(job.size(), 0.0) {}

    std::uint32_t device_count() const override {
        std::uint32_t total = 0;
        for (int r = 1; r < job_.size(); ++r)
            total += devices_[r];
        return total;
    }

    bool serve(ChunkQueue& queue) override {
        bool all = true;
        for (int r = 1; r < job_.size(); ++r) {
            // A rank whose film has arrived is not heard again in this call:
            // its next request belongs to the next one.
            while (!film_arrived_[r]) {
                int waiting = 0;
                MPI_Status status;
                MPI_Iprobe(r, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status);
                if (!waiting)
                    break;
                handle(r, status.MPI_TAG, queue);
            }
            all = all && film_arrived_[r];
        }
        return all;
    }

    double samples_done() const override {
        double total = 0.0;
        for (double d : done_)
            total += d;
        return total;
    }

    void merge_into(Film& film) override {
        for (int r = 1; r < job_.size(); ++r) {
            if (films_[r].pixel_count() > 0)
                film.merge(films_[r]);
            films_[r] = Film();
            film_arrived_[r] = false;
        }
        std::fill(done_.begin(), done_.end(), 0.0); // the next call starts afresh
    }

    std::string describe() const override {
        return std::to_string(device_count()) + (device_count() == 1 ? " device" : " devices") +
               " on " + std::to_string(job_.size() - 1) + " other rank" +
               (job_.size() > 2 ? "s" : "");
    }

    std::vector<DeviceShare> finish(RenderStats& stats) override {
        std::vector<DeviceShare> shares;
        if (broken_)
            return shares; // a rank has failed: the job ends with MPI_Abort
        for (int r = 1; r < job_.size(); ++r) {
            // The rank's next message is a request (or a film not yet taken,
            // after a failure on rank 0): answer it with the end.
            for (;;) {
                MPI_Status status;
                MPI_Probe(r, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
                if (status.MPI_TAG == kRequest) {
                    std::uint64_t completed = 0;
                    MPI_Recv(&completed, 1, MPI_UINT64_T, r, kRequest, MPI_COMM_WORLD,
                             MPI_STATUS_IGNORE);
                    const std::array<std::uint32_t, 3> end{kEnd, 0, 0};
                    MPI_Send(end.data(), 3, MPI_UINT32_T, r, kReply, MPI_COMM_WORLD);
                    break;
                }
                if (status.MPI_TAG == kFilm) {
                    receive_film(r);
                    continue;
                }
                if (status.MPI_TAG == kFailed) {
                    job_.receive_text(r, kFailed);
                    job_.abort_at_exit();
                    return shares;
                }
                throw std::logic_error("MPI: unexpected message from " + job_.name_of(r));
            }
            const nlohmann::json bye = nlohmann::json::parse(job_.receive_text(r, kBye));
            for (const nlohmann::json& share : bye.at("shares"))
                shares.push_back(share_from_json(share));
            const nlohmann::json& counts = bye.at("stats");
            stats.camera_rays += counts.at("camera").get<std::uint64_t>();
            stats.bounce_rays += counts.at("bounce").get<std::uint64_t>();
            stats.shadow_rays += counts.at("shadow").get<std::uint64_t>();
            stats.capped_paths += counts.at("capped").get<std::uint64_t>();
            stats.nonfinite_samples += counts.at("nonfinite").get<std::uint64_t>();
        }
        return shares;
    }

  private:
    void handle(int r, int tag, ChunkQueue& queue) {
        if (tag == kRequest) {
            std::uint64_t completed = 0;
            MPI_Recv(&completed, 1, MPI_UINT64_T, r, kRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            done_[r] += static_cast<double>(completed);
            const std::optional<SampleRange> range = queue.take_without_holding();
            const std::array<std::uint32_t, 3> reply =
                range ? std::array<std::uint32_t, 3>{kChunk, range->first, range->count}
                      : std::array<std::uint32_t, 3>{kDone, 0, 0};
            MPI_Send(reply.data(), 3, MPI_UINT32_T, r, kReply, MPI_COMM_WORLD);
        } else if (tag == kFilm) {
            receive_film(r);
            film_arrived_[r] = true;
        } else if (tag == kFailed) {
            const std::string error = job_.receive_text(r, kFailed);
            job_.abort_at_exit(); // the others cannot be ended in order now
            broken_ = true;
            throw std::runtime_error(job_.name_of(r) + " (" + hosts_[r] + "): " + error);
        } else {
            throw std::logic_error("MPI: unexpected message from " + job_.name_of(r));
        }
    }

    void receive_film(int r) {
        std::uint64_t header = 0;
        MPI_Recv(&header, 1, MPI_UINT64_T, r, kFilm, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (header == 0) {
            films_[r] = Film();
            return;
        }
        // In send_film's order, on one tag: MPI keeps the order of messages
        // between two ranks.
        FilmSums sums;
        job_.receive_doubles(r, kFilm, sums.sum);
        job_.receive_doubles(r, kFilm, sums.sum_squares);
        job_.receive_doubles(r, kFilm, sums.odd_sum);
        job_.receive_counts(r, kFilm, sums.count);
        job_.receive_counts(r, kFilm, sums.odd_count);
        job_.receive_doubles(r, kFilm, sums.aov_sum);
        films_[r] = Film(width_, height_, std::move(sums));
    }

    MpiJob& job_;
    std::vector<std::uint32_t> devices_; // per rank
    std::vector<std::string> hosts_;
    bool broken_ = false;
    int width_;
    int height_;
    std::vector<Film> films_; // this call's, per rank
    std::vector<bool> film_arrived_;
    std::vector<double> done_; // samples per pixel finished this call, per rank
};

// What a rank's samples depend on: the checkpoints' identity (scene
// content, film shape, options with the kernels' build options, version), so
// that a rank started with another scene or other options is caught before
// its samples are mixed into the image.
nlohmann::json fingerprint_json(const CheckpointIdentity& id) {
    return {{"scene", id.scene_hash},
            {"width", id.width},
            {"height", id.height},
            {"options", id.options},
            {"version", id.version}};
}

CheckpointIdentity fingerprint_from_json(const nlohmann::json& j) {
    return {j.at("scene"), j.at("width"), j.at("height"), j.at("options"), j.at("version")};
}

// The first word of `a` that differs from `b`'s ("estimator=camera").
std::string first_difference(const std::string& a, const std::string& b) {
    std::size_t i = 0;
    while (i < a.size() && i < b.size() && a[i] == b[i])
        ++i;
    const std::size_t start = a.rfind(' ', i == 0 ? 0 : i - 1);
    const std::size_t from = start == std::string::npos ? 0 : start + 1;
    const std::size_t end = a.find(' ', i);
    return a.substr(from, end == std::string::npos ? std::string::npos : end - from);
}

// "" if rank r's render is rank 0's, else what differs, in words.
std::string disagreement(const CheckpointIdentity& mine, const CheckpointIdentity& theirs) {
    const auto quote = [](const std::string& word) {
        return "'" + (word.empty() ? std::string("(nothing)") : word) + "'";
    };
    if (theirs.width != mine.width || theirs.height != mine.height)
        return "its film is " + std::to_string(theirs.width) + "x" + std::to_string(theirs.height) +
               ", rank 0's " + std::to_string(mine.width) + "x" + std::to_string(mine.height) +
               " (other --width/--height or scene resolution)";
    if (theirs.scene_hash != mine.scene_hash)
        return "its scene differs from rank 0's (another scene file, or other contents or "
               "meshes)";
    if (theirs.options != mine.options)
        return "its options differ from rank 0's: " +
               quote(first_difference(theirs.options, mine.options)) + " where rank 0 has " +
               quote(first_difference(mine.options, theirs.options));
    if (theirs.version != mine.version)
        return "it runs " + theirs.version + ", rank 0 " + mine.version;
    return "";
}

struct StartReport {
    bool ok = false;
    std::uint32_t devices = 0;
    std::string host;
    std::string error;
    CheckpointIdentity fingerprint; // when ok
};

std::vector<StartReport> hear_start_reports(const MpiJob& job) {
    std::vector<StartReport> reports(job.size());
    for (int r = 1; r < job.size(); ++r) {
        const nlohmann::json j = nlohmann::json::parse(job.receive_text(r, kStart));
        reports[r] = {j.at("ok"), j.at("devices"), j.at("host"), j.at("error"), {}};
        if (reports[r].ok)
            reports[r].fingerprint = fingerprint_from_json(j.at("fingerprint"));
    }
    return reports;
}

void answer_start(MpiJob& job, bool go) {
    int value = go ? 1 : 0;
    for (int r = 1; r < job.size(); ++r)
        MPI_Send(&value, 1, MPI_INT, r, kGo, MPI_COMM_WORLD);
    job.set_started();
}

} // namespace

void refuse_start(MpiJob& job) {
    hear_start_reports(job);
    answer_start(job, false);
}

std::unique_ptr<MultiDeviceRenderer> open_mpi_renderer(MpiJob& job, const Scene& scene,
                                                       const std::string& devices,
                                                       const IntegratorOptions& options,
                                                       bool profiling) {
    std::unique_ptr<MultiDeviceRenderer> renderer;
    std::exception_ptr failure;
    try {
        renderer = std::make_unique<MultiDeviceRenderer>(select_devices(devices), scene, options,
                                                         profiling);
    } catch (...) {
        failure = std::current_exception();
    }
    const std::vector<StartReport> reports = hear_start_reports(job);
    bool go = !failure;
    for (int r = 1; r < job.size(); ++r)
        go = go && reports[r].ok;
    // Every rank must render the same image, or its samples would be mixed
    // silently into another's.
    std::string disagreeing;
    if (go) {
        const CheckpointIdentity mine =
            checkpoint_identity(scene, options, renderer->integrator().program().options);
        for (int r = 1; r < job.size() && disagreeing.empty(); ++r)
            if (const std::string what = disagreement(mine, reports[r].fingerprint); !what.empty())
                disagreeing = job.name_of(r) + " (" + reports[r].host +
                              ") does not render what rank 0 does: " + what;
        go = disagreeing.empty();
    }
    answer_start(job, go);
    if (failure)
        std::rethrow_exception(failure);
    for (int r = 1; r < job.size(); ++r)
        if (!reports[r].ok)
            throw std::runtime_error(job.name_of(r) + " (" + reports[r].host +
                                     "): " + reports[r].error);
    if (!disagreeing.empty())
        throw std::runtime_error(disagreeing);

    std::vector<std::uint32_t> per_rank(job.size(), 0);
    std::vector<std::string> hosts(job.size(), job.host());
    for (int r = 1; r < job.size(); ++r) {
        per_rank[r] = reports[r].devices;
        hosts[r] = reports[r].host;
    }
    renderer->set_peers(std::make_unique<MpiPeers>(job, std::move(per_rank), std::move(hosts),
                                                   scene.camera.width, scene.camera.height));
    return renderer;
}

int run_mpi_worker(MpiJob& job, const std::function<Scene()>& load_scene,
                   const std::string& devices, const IntegratorOptions& options) {
    std::unique_ptr<MultiDeviceRenderer> renderer;
    int width = 0, height = 0;
    nlohmann::json report = {{"ok", true}, {"devices", 0}, {"host", job.host()}, {"error", ""}};
    const std::string who = job.name_of(job.rank()) + " (" + job.host() + ")";
    try {
        const Scene scene = load_scene();
        width = scene.camera.width;
        height = scene.camera.height;
        renderer = std::make_unique<MultiDeviceRenderer>(select_devices(devices), scene, options);
        renderer->set_failure_reporter([who](const std::string& line) {
            std::cerr << "wavepath: warning: " << who << ": " << line << "\n";
        });
        report["devices"] = renderer->device_count();
        report["fingerprint"] = fingerprint_json(
            checkpoint_identity(scene, options, renderer->integrator().program().options));
    } catch (...) {
        report["ok"] = false;
        report["error"] = exception_text(std::current_exception());
    }
    job.send_text(0, kStart, report.dump());
    int go = 0;
    MPI_Recv(&go, 1, MPI_INT, 0, kGo, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    // A rank that gives up exits with 0: a non-zero exit makes mpirun kill
    // the job at once, before rank 0 has printed the error and set the
    // job's exit status.
    if (!go || !renderer)
        return 0;

    for (;;) {
        RemoteChunkSource source(job);
        Film film(width, height);
        try {
            renderer->render_from(source, film);
        } catch (...) {
            job.send_text(0, kFailed, exception_text(std::current_exception()));
            return 0; // rank 0 ends the job with the error (see above)
        }
        if (source.ended())
            break;
        send_film(job, film, film.total_samples() > 0);
    }
    nlohmann::json shares = nlohmann::json::array();
    for (DeviceShare share : renderer->shares()) {
        share.rank = job.rank();
        share.host = job.host();
        shares.push_back(share_json(share));
    }
    const RenderStats stats = renderer->stats();
    const nlohmann::json bye = {{"shares", shares},
                                {"stats",
                                 {{"camera", stats.camera_rays},
                                  {"bounce", stats.bounce_rays},
                                  {"shadow", stats.shadow_rays},
                                  {"capped", stats.capped_paths},
                                  {"nonfinite", stats.nonfinite_samples}}}};
    job.send_text(0, kBye, bye.dump());
    return 0;
}

} // namespace wp
