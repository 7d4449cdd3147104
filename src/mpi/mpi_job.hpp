// The MPI job this process belongs to, if any (compiled only where CMake
// found MPI).
//
// MPI is initialised only when a launcher started the process: mpirun sets
// OMPI_COMM_WORLD_SIZE (Open MPI), PMI_SIZE (MPICH, Slurm) or PMIX_RANK
// (PMIx). Otherwise wavepath is a job of one and never calls MPI_Init, whose
// singleton start-up (Open MPI 4.1 starts a helper daemon) takes about 0.7 s
// on this project's machine: every plain command would pay it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace wp {

class MpiJob {
  public:
    // The process's job, initialised on first use (MPI_THREAD_SERIALIZED: the
    // device threads of a rank talk to rank 0, one at a time).
    static MpiJob& get();

    int rank() const { return rank_; }
    int size() const { return size_; }
    const std::string& host() const { return host_; }
    // "rank 1 of 4 (host)"
    std::string name_of(int rank) const;

    // The render failed on some rank and the others cannot be told in order:
    // the job ends with MPI_Abort rather than MPI_Finalize.
    void abort_at_exit() { abort_ = true; }
    // Rank 0 has answered the ranks' start-up reports (mpi_render.cpp); if
    // it has not when the process ends, it tells them to give up.
    void set_started() { started_ = true; }
    bool started() const { return started_; }

    // Point-to-point messages of bytes and of arrays, any length.
    void send_text(int to, int tag, const std::string& text) const;
    std::string receive_text(int from, int tag) const;
    void send_doubles(int to, int tag, const std::vector<double>& values) const;
    void receive_doubles(int from, int tag, std::vector<double>& values) const;
    void send_counts(int to, int tag, const std::vector<std::uint64_t>& values) const;
    void receive_counts(int from, int tag, std::vector<std::uint64_t>& values) const;

    MpiJob(const MpiJob&) = delete;
    MpiJob& operator=(const MpiJob&) = delete;

  private:
    MpiJob();
    ~MpiJob();

    bool initialised_ = false;
    int rank_ = 0;
    int size_ = 1;
    std::string host_;
    bool abort_ = false;
    bool started_ = false;
};

} // namespace wp
