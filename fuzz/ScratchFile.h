#pragma once
// The fuzz input as a file, for readers that take a path (DICOM, MetaImage,
// NIfTI, InVesalius): one file of a fixed name (the extension matters to some
// readers) in a folder of this process, on /dev/shm when there is one so that
// each input costs no disk. Rewritten for every input; removed at exit.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace lucent::fuzz {

class ScratchFile {
public:
    explicit ScratchFile(const std::string& name) {
        namespace fs = std::filesystem;
        const fs::path base =
            fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
        dir_ = base / ("lucent-fuzz-" + std::to_string(::getpid()));
        fs::create_directories(dir_);
        path_ = (dir_ / name).string();
    }
    ~ScratchFile() {
        std::error_code ignored;
        std::filesystem::remove_all(dir_, ignored);
    }
    ScratchFile(const ScratchFile&) = delete;
    ScratchFile& operator=(const ScratchFile&) = delete;

    // Replaces the file's content with the input.
    const std::string& write(const std::uint8_t* data, std::size_t size) {
        std::ofstream out(path_, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out.flush()) {
            throw std::runtime_error("fuzz: cannot write the input to " + path_);
        }
        return path_;
    }
    const std::string& path() const { return path_; }
    std::filesystem::path folder() const { return dir_; }

private:
    std::filesystem::path dir_;
    std::string path_;
};

} // namespace lucent::fuzz
