// JPEG-LS is decoded by DCMTK's dcmdjpls in a child process: GDCM's codec
// rejects some valid streams (NEMA WG04 MR1_JLSL is one) and leaks its copy of
// every stream it fails on (FrameDecoder.cpp). DCMTK cannot decode in this
// process: its bundled CharLS and the system CharLS that GDCM uses export the
// same JpegLs* symbols with different ABIs, so one of them would call the other.
#include "core/dicom/FrameDecoder.h"

#include <cstdlib>
#include <filesystem>

#include <spawn.h>
#include <sys/wait.h>

#include "core/dicom/DicomStructure.h"
#include "core/io/LoadControl.h"

extern char** environ;

namespace lucent {
namespace {

namespace fs = std::filesystem;

// A private temporary folder, removed with everything in it.
class TemporaryFolder {
public:
    TemporaryFolder() {
        std::string pattern = (fs::temp_directory_path() / "lucent-jpegls-XXXXXX").string();
        if (::mkdtemp(pattern.data()) != nullptr) {
            path_ = pattern;
        }
    }
    ~TemporaryFolder() {
        std::error_code ec;
        if (!path_.empty()) {
            fs::remove_all(path_, ec);
        }
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

int run(const std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (const std::string& a : args) {
        argv.push_back(const_cast<char*>(a.c_str()));
    }
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (::posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) {
        return -1;
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            return -1;
        }
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace

bool isJpegLs(const std::string& transferSyntax) {
    return transferSyntax == "1.2.840.10008.1.2.4.80" || transferSyntax == "1.2.840.10008.1.2.4.81";
}

DecodedFrames decodeJpegLsWithDcmtk(const std::string& file, const PixelLayout& expected,
                                    int frames) {
    const TemporaryFolder tmp;
    if (tmp.path().empty()) {
        throw LoadError(file + ": cannot create a temporary folder for JPEG-LS decoding");
    }
    const fs::path out = tmp.path() / "decoded.dcm";
    if (run({"dcmdjpls", "--write-xfer-little", "--color-by-pixel", file, out.string()}) != 0) {
        throw LoadError(file + ": dcmdjpls could not decode the JPEG-LS data");
    }
    const DicomStructure st = checkDicomStructure(out.string());
    DecodedFrames decoded;
    decoded.format = rawFormatOf(expected);
    decoded.frameBytes = static_cast<std::size_t>(expected.rows) * expected.columns *
                         static_cast<std::size_t>(expected.bitsAllocated / 8) *
                         static_cast<std::size_t>(expected.samplesPerPixel);
    decoded.photometric = expected.photometric; // dcmdjpls keeps the colour model
    const std::size_t bytes = decoded.frameBytes * static_cast<std::size_t>(frames);
    if (!st.ok || !st.hasPixelData || st.encapsulated || st.pixelLength < bytes) {
        throw LoadError(file + ": dcmdjpls output has no usable pixel data");
    }
    decoded.buffer.resize(bytes);
    readNativeFrame(out.string(), st.pixelOffset, bytes, decoded.buffer.data());
    return decoded;
}

} // namespace lucent
