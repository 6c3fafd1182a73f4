#pragma once
// MPI for the life of a process that renders with others (docs/distributed.md):
// initialised on construction, finalised on destruction. One per process.

namespace lucent {

// Which threads call MPI (and IceT): the one that made the session
// (funnelled), or any one at a time (serialised: a server's rank 0 starts in
// its main thread and renders on its render thread).
enum class MpiThreads { Funnelled, Serialised };

class MpiSession {
public:
    // Throws std::runtime_error when MPI cannot be initialised with the
    // threads asked for, or when a session already exists in this process.
    explicit MpiSession(MpiThreads threads = MpiThreads::Funnelled);
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
