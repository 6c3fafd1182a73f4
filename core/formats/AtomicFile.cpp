#include "core/formats/AtomicFile.h"

#include <random>
#include <stdexcept>
#include <string>
#include <system_error>

namespace lucent::formats {

namespace {

std::filesystem::path tempNameFor(const std::filesystem::path& target) {
    std::random_device rd;
    const auto tag = std::to_string(rd()) + std::to_string(rd());
    return target.parent_path() / ("." + target.filename().string() + ".tmp" + tag);
}

} // namespace

AtomicFileWriter::AtomicFileWriter(std::filesystem::path target)
    : AtomicFileWriter(target, tempNameFor(target)) {}

AtomicFileWriter::AtomicFileWriter(std::filesystem::path target, std::filesystem::path temporary)
    : target_(std::move(target)), temp_(std::move(temporary)) {
    out_.open(temp_, std::ios::binary | std::ios::trunc);
    if (!out_) {
        throw std::runtime_error(target_.string() + ": cannot create " + temp_.string());
    }
}

AtomicFileWriter::~AtomicFileWriter() {
    if (!committed_) {
        out_.close();
        std::error_code ec;
        std::filesystem::remove(temp_, ec);
    }
}

void AtomicFileWriter::finish() {
    out_.flush();
    const bool ok = out_.good();
    out_.close();
    if (!ok || out_.fail()) {
        throw std::runtime_error(target_.string() + ": write failed (disk full or no permission?)");
    }
    finished_ = true;
}

void AtomicFileWriter::commit() {
    if (!finished_) {
        finish();
    }
    std::error_code ec;
    std::filesystem::rename(temp_, target_, ec);
    if (ec) {
        throw std::runtime_error(target_.string() +
                                 ": cannot rename the finished file into place: " + ec.message());
    }
    committed_ = true;
}

} // namespace lucent::formats
