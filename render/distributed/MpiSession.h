#pragma once
// MPI for the life of a process that renders with others (docs/distributed.md):
// initialised on construction (threads funnelled: MPI and IceT are called from
// one thread), finalised on destruction. One per process.

namespace lucent {

class MpiSession {
public:
    // Throws std::runtime_error when MPI cannot be initialised, or when a
    // session already exists in this process.
    MpiSession();
    ~MpiSession();
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;

    // This process's rank in MPI_COMM_WORLD and the number of processes.
    int rank() const { return rank_; }
    int size() const { return size_; }

    // Whether MPI is initialised and not yet finalised in this process.
    static bool active();

private:
    int rank_ = 0;
    int size_ = 1;
};

} // namespace lucent
