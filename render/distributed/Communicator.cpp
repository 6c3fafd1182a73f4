#include "render/distributed/Communicator.h"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

namespace lucent {

struct Communicator::Handle {
    MPI_Comm comm = MPI_COMM_NULL;
    ~Handle() {
        int finalised = 0;
        MPI_Finalized(&finalised);
        if (comm != MPI_COMM_NULL && finalised == 0) {
            MPI_Comm_free(&comm);
        }
    }
};

namespace {

void check(int code, const char* call) {
    if (code == MPI_SUCCESS) {
        return;
    }
    char text[MPI_MAX_ERROR_STRING] = {};
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw std::runtime_error(std::string("MPI: ") + call + " failed: " + text);
}

} // namespace

Communicator Communicator::world() {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (initialised == 0) {
        throw std::runtime_error("MPI: not initialised (no MpiSession)");
    }
    auto handle = std::make_unique<Handle>();
    check(MPI_Comm_dup(MPI_COMM_WORLD, &handle->comm), "MPI_Comm_dup");
    check(MPI_Comm_set_errhandler(handle->comm, MPI_ERRORS_RETURN), "MPI_Comm_set_errhandler");
    return Communicator(std::move(handle));
}

Communicator::Communicator(std::unique_ptr<Handle> handle) : handle_(std::move(handle)) {
    check(MPI_Comm_rank(handle_->comm, &rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(handle_->comm, &size_), "MPI_Comm_size");
    MPI_Comm node = MPI_COMM_NULL;
    check(MPI_Comm_split_type(handle_->comm, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node),
          "MPI_Comm_split_type");
    MPI_Comm_rank(node, &localRank_);
    MPI_Comm_free(&node);
}

Communicator::~Communicator() = default;
Communicator::Communicator(Communicator&&) noexcept = default;
Communicator& Communicator::operator=(Communicator&&) noexcept = default;

void Communicator::broadcast(std::vector<std::byte>& bytes, int root) const {
    std::uint64_t size = bytes.size();
    check(MPI_Bcast(&size, 1, MPI_UINT64_T, root, handle_->comm), "MPI_Bcast");
    bytes.resize(size);
    // In pieces of at most 1 GiB: MPI counts are ints.
    constexpr std::uint64_t kPiece = 1ull << 30;
    for (std::uint64_t at = 0; at < size; at += kPiece) {
        const int n = int(std::min(kPiece, size - at));
        check(MPI_Bcast(bytes.data() + at, n, MPI_BYTE, root, handle_->comm), "MPI_Bcast");
    }
}

void Communicator::broadcast(std::string& text, int root) const {
    std::vector<std::byte> bytes(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        bytes[i] = std::byte(text[i]);
    }
    broadcast(bytes, root);
    text.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

void Communicator::broadcastPolled(std::string& text, int root,
                                   std::chrono::microseconds poll) const {
    // A non-blocking broadcast of the size (every rank must use the same kind
    // of collective), tested with sleeps in between; then the text itself.
    if (text.size() > std::size_t(std::numeric_limits<int>::max())) {
        throw std::invalid_argument("MPI: a polled broadcast of " + std::to_string(text.size()) +
                                    " bytes (at most 2 GiB)");
    }
    std::uint64_t size = text.size();
    MPI_Request request = MPI_REQUEST_NULL;
    check(MPI_Ibcast(&size, 1, MPI_UINT64_T, root, handle_->comm, &request), "MPI_Ibcast");
    for (;;) {
        int done = 0;
        check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
        if (done != 0) {
            break;
        }
        std::this_thread::sleep_for(poll);
    }
    text.resize(size);
    if (size > 0) {
        check(MPI_Bcast(text.data(), int(size), MPI_CHAR, root, handle_->comm), "MPI_Bcast");
    }
}

void Communicator::allMin(std::span<double> values) const {
    check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_MIN,
                        handle_->comm),
          "MPI_Allreduce");
}

void Communicator::allMax(std::span<double> values) const {
    check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_MAX,
                        handle_->comm),
          "MPI_Allreduce");
}

void Communicator::allSum(std::span<double> values) const {
    check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_SUM,
                        handle_->comm),
          "MPI_Allreduce");
}

double Communicator::allMin(double v) const {
    allMin(std::span<double>(&v, 1));
    return v;
}

double Communicator::allMax(double v) const {
    allMax(std::span<double>(&v, 1));
    return v;
}

std::vector<double> Communicator::allGather(double v) const {
    std::vector<double> out(static_cast<std::size_t>(size_), 0.0);
    check(MPI_Allgather(&v, 1, MPI_DOUBLE, out.data(), 1, MPI_DOUBLE, handle_->comm),
          "MPI_Allgather");
    return out;
}

void Communicator::sumTo(std::span<float> values, int root) const {
    const int n = int(values.size());
    if (rank_ == root) {
        check(MPI_Reduce(MPI_IN_PLACE, values.data(), n, MPI_FLOAT, MPI_SUM, root, handle_->comm),
              "MPI_Reduce");
    } else {
        check(MPI_Reduce(values.data(), nullptr, n, MPI_FLOAT, MPI_SUM, root, handle_->comm),
              "MPI_Reduce");
    }
}

std::vector<std::vector<std::byte>>
Communicator::allGather(std::span<const std::byte> bytes) const {
    const int mine = int(bytes.size());
    std::vector<int> sizes(std::size_t(size_), 0);
    check(MPI_Allgather(&mine, 1, MPI_INT, sizes.data(), 1, MPI_INT, handle_->comm),
          "MPI_Allgather");
    std::vector<int> offsets(std::size_t(size_), 0);
    int total = 0;
    for (int r = 0; r < size_; ++r) {
        offsets[std::size_t(r)] = total;
        total += sizes[std::size_t(r)];
    }
    std::vector<std::byte> all(static_cast<std::size_t>(total));
    check(MPI_Allgatherv(bytes.data(), mine, MPI_BYTE, all.data(), sizes.data(), offsets.data(),
                         MPI_BYTE, handle_->comm),
          "MPI_Allgatherv");
    std::vector<std::vector<std::byte>> out(static_cast<std::size_t>(size_));
    for (int r = 0; r < size_; ++r) {
        const auto begin = all.begin() + offsets[std::size_t(r)];
        out[std::size_t(r)].assign(begin, begin + sizes[std::size_t(r)]);
    }
    return out;
}

void Communicator::barrier() const {
    check(MPI_Barrier(handle_->comm), "MPI_Barrier");
}

void Communicator::abort(const std::string& message, int code) const {
    std::fprintf(stderr, "rank %d: %s\n", rank_, message.c_str());
    std::fflush(stderr);
    MPI_Abort(handle_->comm, code);
    std::abort(); // MPI_Abort does not return
}

int Communicator::fortranHandle() const {
    return int(MPI_Comm_c2f(handle_->comm));
}

} // namespace lucent
