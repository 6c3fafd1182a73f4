#pragma once

// Internal to core/formats: files that appear complete or not at all.

#include <filesystem>
#include <fstream>

namespace lucent::formats {

// Writes to a temporary file beside target; commit() renames it onto target.
// A writer destroyed without commit() removes its temporary file.
class AtomicFileWriter {
public:
    explicit AtomicFileWriter(std::filesystem::path target);
    // With the temporary file named by the caller (e.g. one whose name a study store keeps
    // while its writer runs: the target's name and ".part").
    AtomicFileWriter(std::filesystem::path target, std::filesystem::path temporary);
    ~AtomicFileWriter();
    AtomicFileWriter(const AtomicFileWriter&) = delete;
    AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

    std::ostream& stream() { return out_; }
    // Flushes and closes the temporary file, checking every write succeeded.
    // Throws std::runtime_error naming the target on failure.
    void finish();
    // Renames the finished temporary file onto the target.
    void commit();

private:
    std::filesystem::path target_;
    std::filesystem::path temp_;
    std::ofstream out_;
    bool finished_ = false;
    bool committed_ = false;
};

} // namespace lucent::formats
