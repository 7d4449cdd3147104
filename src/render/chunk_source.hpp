// Handing out the samples of a render to several devices in chunks.
//
// A chunk is a range of sample indices over every pixel: the kernels take a
// first sample and a count (WpFrame), and random numbers depend only on
// (seed, pixel, sample, bounce, dimension), so any split of the samples into
// chunks, rendered on any devices, sums to the same estimate as one device
// rendering them all (up to float rounding of the sums). Chunks are taken
// on demand, so a faster device takes more of them, and they shrink as the
// samples run out (guided self-scheduling: a share of what is left), so that
// the last chunk is small and no device waits long for the slowest.
//
// A chunk of samples rather than of pixels needs no kernel change; its cost
// is that the smallest chunk is one sample per pixel, so a render of fewer
// samples per pixel than devices leaves some of them idle
// (docs/multi-device.md).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>

namespace wp {

struct SampleRange {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

// Where device threads take their chunks. take() blocks while every range
// has been handed out but a device still holds one that it may give back
// (it fails), and returns nothing only when no work is left and none can
// come back. Thread-safe.
class ChunkSource {
  public:
    virtual ~ChunkSource() = default;

    std::optional<SampleRange> take();
    // The chunk is rendered and in its device's film.
    void complete(SampleRange range);
    // The device failed: the chunk goes to the next device that asks.
    void give_back(SampleRange range);

    // Hands out nothing more (the render is being abandoned): the devices
    // stop after their current chunks.
    void cancel();

    // Ranges given back and not taken since (when every device failed).
    std::uint64_t samples_given_back() const;

  protected:
    // New ranges once the given-back ones are used up; nothing when there
    // are no more. Called without the lock, by one thread at a time, with
    // the samples per pixel completed since its last call.
    virtual std::optional<SampleRange> next_range(std::uint64_t completed) = 0;

    // For a source that also feeds other processes (mpi_peers.cpp): a range
    // for them, without waiting and without counting it as held here.
    std::optional<SampleRange> take_without_holding();

  private:
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<SampleRange> given_back_;
    std::uint32_t held_ = 0; // chunks taken and not yet completed or given back
    std::uint64_t completed_unreported_ = 0;
    bool exhausted_ = false; // next_range has said there are no more
    bool refilling_ = false; // a thread is inside next_range
};

// The samples [first, first + count) in guided chunks for `workers` devices:
// each chunk is what is left divided by twice the number of workers, at
// least one sample per pixel (one worker takes everything at once).
class ChunkQueue : public ChunkSource {
  public:
    ChunkQueue(std::uint32_t first, std::uint32_t count, std::uint32_t workers);

    // Size of the next chunk when `left` samples remain.
    static std::uint32_t chunk_size(std::uint32_t left, std::uint32_t workers);

    using ChunkSource::take_without_holding;

  protected:
    std::optional<SampleRange> next_range(std::uint64_t completed) override;

  private:
    std::uint32_t next_;
    std::uint32_t end_;
    std::uint32_t workers_;
};

} // namespace wp
