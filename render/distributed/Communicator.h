#pragma once
// A communicator of the ranks that render one volume together: a duplicate of
// MPI_COMM_WORLD (so that its traffic never meets another library's), with the
// few collectives the distributed renderer needs. Every rank calls every
// collective, in the same order. Errors throw std::runtime_error naming the
// call and MPI's message.

#include <chrono>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace lucent {

class Communicator {
public:
    // A duplicate of MPI_COMM_WORLD; MPI must be initialised (MpiSession).
    static Communicator world();
    ~Communicator();
    Communicator(Communicator&&) noexcept;
    Communicator& operator=(Communicator&&) noexcept;
    Communicator(const Communicator&) = delete;
    Communicator& operator=(const Communicator&) = delete;

    int rank() const { return rank_; }
    int size() const { return size_; }
    // The rank among the ranks on this node (shared memory): which GPU a rank
    // takes on a node with several.
    int localRank() const { return localRank_; }

    // root's bytes to every rank (the size first).
    void broadcast(std::vector<std::byte>& bytes, int root) const;
    void broadcast(std::string& text, int root) const;
    // As broadcast(text), but a rank that waits for root sleeps between looks
    // (about every `poll`) instead of spinning in MPI: for ranks that wait
    // long for the next command (a distributed server's idle ranks).
    void broadcastPolled(std::string& text, int root, std::chrono::microseconds poll) const;
    // The smallest, largest or sum of every rank's values, element by element, on every rank.
    void allMin(std::span<double> values) const;
    void allMax(std::span<double> values) const;
    void allSum(std::span<double> values) const;
    double allMin(double v) const;
    double allMax(double v) const;
    // Every rank's value, in rank order, on every rank.
    std::vector<double> allGather(double v) const;
    // The sum over ranks of `values`, element by element, on `root` (elsewhere
    // `values` is left as it is).
    void sumTo(std::span<float> values, int root) const;
    // Every rank's bytes, in rank order, on every rank.
    std::vector<std::vector<std::byte>> allGather(std::span<const std::byte> bytes) const;
    void barrier() const;

    // Ends every rank of the job (MPI_Abort) with `code`, after writing
    // "rank R: message" to stderr.
    [[noreturn]] void abort(const std::string& message, int code) const;

    // MPI's Fortran handle of the communicator (MPI_Comm_c2f): how IceT's
    // communicator is made from it without MPI types in this header.
    int fortranHandle() const;

private:
    struct Handle;
    explicit Communicator(std::unique_ptr<Handle> handle);
    std::unique_ptr<Handle> handle_;
    int rank_ = 0;
    int size_ = 1;
    int localRank_ = 0;
};

} // namespace lucent
