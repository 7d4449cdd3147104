#include "mpi/mpi_job.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include <mpi.h>

#include "mpi/mpi_render.hpp"

namespace wp {
namespace {

bool launched_by_mpirun() {
    for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(variable))
            return true;
    return false;
}

// Large arrays go in pieces: MPI counts are ints.
constexpr std::size_t kPiece = std::size_t{1} << 26;

template <typename T>
void send_array(int to, int tag, const std::vector<T>& values, MPI_Datatype type) {
    std::uint64_t size = values.size();
    MPI_Send(&size, 1, MPI_UINT64_T, to, tag, MPI_COMM_WORLD);
    for (std::size_t at = 0; at < values.size(); at += kPiece)
        MPI_Send(values.data() + at, static_cast<int>(std::min(kPiece, values.size() - at)), type,
                 to, tag, MPI_COMM_WORLD);
}

template <typename T>
void receive_array(int from, int tag, std::vector<T>& values, MPI_Datatype type) {
    std::uint64_t size = 0;
    MPI_Recv(&size, 1, MPI_UINT64_T, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    values.resize(size);
    for (std::size_t at = 0; at < values.size(); at += kPiece)
        MPI_Recv(values.data() + at, static_cast<int>(std::min(kPiece, values.size() - at)), type,
                 from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

} // namespace

MpiJob& MpiJob::get() {
    static MpiJob job;
    return job;
}

MpiJob::MpiJob() {
    if (!launched_by_mpirun())
        return;
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
    initialised_ = true;
    if (provided < MPI_THREAD_SERIALIZED)
        throw std::runtime_error("the MPI library does not allow MPI calls from several threads "
                                 "(MPI_THREAD_SERIALIZED)");
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    char name[MPI_MAX_PROCESSOR_NAME] = {};
    int length = 0;
    MPI_Get_processor_name(name, &length);
    host_.assign(name, static_cast<std::size_t>(length));
}

MpiJob::~MpiJob() {
    if (!initialised_)
        return;
    if (abort_) {
        MPI_Abort(MPI_COMM_WORLD, 1);
        return;
    }
    if (rank_ == 0 && size_ > 1 && !started_)
        refuse_start(*this); // rank 0 failed before it could answer the others
    MPI_Finalize();
}

std::string MpiJob::name_of(int rank) const {
    return "rank " + std::to_string(rank) + " of " + std::to_string(size_);
}

void MpiJob::send_text(int to, int tag, const std::string& text) const {
    MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD);
}

std::string MpiJob::receive_text(int from, int tag) const {
    MPI_Status status;
    MPI_Probe(from, tag, MPI_COMM_WORLD, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_CHAR, &count);
    std::string text(static_cast<std::size_t>(count), '\0');
    MPI_Recv(text.data(), count, MPI_CHAR, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return text;
}

void MpiJob::send_doubles(int to, int tag, const std::vector<double>& values) const {
    send_array(to, tag, values, MPI_DOUBLE);
}
void MpiJob::receive_doubles(int from, int tag, std::vector<double>& values) const {
    receive_array(from, tag, values, MPI_DOUBLE);
}
void MpiJob::send_counts(int to, int tag, const std::vector<std::uint64_t>& values) const {
    send_array(to, tag, values, MPI_UINT64_T);
}
void MpiJob::receive_counts(int from, int tag, std::vector<std::uint64_t>& values) const {
    receive_array(from, tag, values, MPI_UINT64_T);
}

} // namespace wp
