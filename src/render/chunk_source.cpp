#include "render/chunk_source.hpp"

#include <algorithm>

namespace wp {

std::optional<SampleRange> ChunkSource::take() {
    std::unique_lock lock(mutex_);
    for (;;) {
        if (!given_back_.empty()) {
            const SampleRange range = given_back_.front();
            given_back_.pop_front();
            ++held_;
            return range;
        }
        if (!exhausted_ && !refilling_) {
            // Ask for more outside the lock: for an MPI rank that is a round
            // trip to rank 0, during which the other devices complete chunks.
            refilling_ = true;
            const std::uint64_t completed = completed_unreported_;
            completed_unreported_ = 0;
            lock.unlock();
            std::optional<SampleRange> range;
            try {
                range = next_range(completed);
            } catch (...) {
                lock.lock();
                refilling_ = false;
                exhausted_ = true;
                changed_.notify_all();
                throw;
            }
            lock.lock();
            refilling_ = false;
            if (range) {
                ++held_;
                changed_.notify_all();
                return range;
            }
            exhausted_ = true;
            changed_.notify_all();
            continue;
        }
        if (exhausted_ && held_ == 0)
            return std::nullopt; // nothing left, and nothing out that could come back
        changed_.wait(lock);
    }
}

std::optional<SampleRange> ChunkSource::take_without_holding() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return !refilling_; });
    if (!given_back_.empty()) {
        const SampleRange range = given_back_.front();
        given_back_.pop_front();
        return range;
    }
    if (exhausted_)
        return std::nullopt;
    refilling_ = true;
    lock.unlock();
    std::optional<SampleRange> range = next_range(0);
    lock.lock();
    refilling_ = false;
    if (!range)
        exhausted_ = true;
    changed_.notify_all();
    return range;
}

void ChunkSource::complete(SampleRange range) {
    std::lock_guard lock(mutex_);
    --held_;
    completed_unreported_ += range.count;
    changed_.notify_all();
}

void ChunkSource::give_back(SampleRange range) {
    std::lock_guard lock(mutex_);
    --held_;
    given_back_.push_back(range);
    changed_.notify_all();
}

void ChunkSource::cancel() {
    std::lock_guard lock(mutex_);
    exhausted_ = true;
    given_back_.clear();
    changed_.notify_all();
}

std::uint64_t ChunkSource::samples_given_back() const {
    std::lock_guard lock(mutex_);
    std::uint64_t samples = 0;
    for (const SampleRange& range : given_back_)
        samples += range.count;
    return samples;
}

ChunkQueue::ChunkQueue(std::uint32_t first, std::uint32_t count, std::uint32_t workers)
    : next_(first), end_(first + count), workers_(std::max(1u, workers)) {}

std::uint32_t ChunkQueue::chunk_size(std::uint32_t left, std::uint32_t workers) {
    if (workers <= 1)
        return left; // alone, the whole range at once (no wave ends early)
    return std::max(1u, left / (2 * workers));
}

std::optional<SampleRange> ChunkQueue::next_range(std::uint64_t) {
    if (next_ >= end_)
        return std::nullopt;
    const std::uint32_t count = std::min(chunk_size(end_ - next_, workers_), end_ - next_);
    const SampleRange range{next_, count};
    next_ += count;
    return range;
}

} // namespace wp
