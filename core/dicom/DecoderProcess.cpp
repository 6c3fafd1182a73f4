#include "core/dicom/DecoderProcess.h"

#include <array>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/dicom/DecoderMessages.h"
#include "core/io/LoadControl.h"

extern char** environ;

namespace lucent {

namespace fs = std::filesystem;

std::string frameDecoderExecutable() {
    if (const char* env = std::getenv("LUCENT_FRAME_DECODER"); env != nullptr && *env != '\0') {
        return env;
    }
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    std::vector<fs::path> candidates;
    if (!ec) {
        candidates.push_back(self.parent_path() / "lucent-frame-decoder");
        candidates.push_back(self.parent_path().parent_path() /
                             "libexec/lucent/lucent-frame-decoder");
    }
    candidates.push_back(fs::path(LUCENT_LIBEXEC_DIR) / "lucent-frame-decoder");
    for (const fs::path& candidate : candidates) {
        if (::access(candidate.c_str(), X_OK) == 0) {
            return candidate.lexically_normal().string();
        }
    }
    return {};
}

DecoderProcess::DecoderProcess(std::chrono::milliseconds timeout, int requestsPerChild)
    : timeout_(timeout), requestsPerChild_(requestsPerChild) {}

DecoderProcess::~DecoderProcess() {
    if (socket_ >= 0) {
        ::close(socket_); // the child reads end of input and exits
        socket_ = -1;
    }
    stop();
}

void DecoderProcess::start() {
    const std::string program = frameDecoderExecutable();
    if (program.empty()) {
        throw LoadError("lucent-frame-decoder was not found (beside this program or in " +
                        std::string(LUCENT_LIBEXEC_DIR) + "; LUCENT_FRAME_DECODER names another)");
    }
    std::array<int, 2> ends{};
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends.data()) != 0) {
        throw LoadError("cannot make a socket for lucent-frame-decoder: " +
                        std::string(std::strerror(errno)));
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, ends[1], STDIN_FILENO);
    posix_spawn_file_actions_adddup2(&actions, ends[1], STDOUT_FILENO);
    // The codecs' own complaints about damaged streams are not the user's: the
    // reply says what went wrong.
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    std::array<char*, 2> argv{const_cast<char*>(program.c_str()), nullptr};
    const int rc = ::posix_spawn(&pid_, program.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(ends[1]);
    if (rc != 0) {
        ::close(ends[0]);
        pid_ = 0;
        throw LoadError("cannot start " + program + ": " + std::strerror(rc));
    }
    socket_ = ends[0];
}

void DecoderProcess::stop() {
    if (socket_ >= 0) {
        ::close(socket_);
        socket_ = -1;
    }
    if (pid_ > 0) {
        ::kill(pid_, SIGKILL);
        while (::waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
        }
        pid_ = 0;
    }
}

std::string DecoderProcess::howItEnded() {
    if (socket_ >= 0) {
        ::close(socket_);
        socket_ = -1;
    }
    int status = 0;
    pid_t done = 0;
    while ((done = ::waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
    }
    pid_ = 0;
    if (done > 0 && WIFSIGNALED(status)) {
        return "stopped by signal " + std::to_string(WTERMSIG(status)) + " (" +
               strsignal(WTERMSIG(status)) + ")";
    }
    if (done > 0 && WIFEXITED(status)) {
        return "exited with status " + std::to_string(WEXITSTATUS(status));
    }
    return "ended";
}

DecodedFrames DecoderProcess::decode(const std::string& file, const PixelLayout& expected,
                                     int frames) {
    if (pid_ > 0 && ::waitpid(pid_, nullptr, WNOHANG) == pid_) {
        pid_ = 0; // it ended since the last file (killed, out of memory)
        ::close(socket_);
        socket_ = -1;
    }
    if (pid_ > 0 && served_ >= requestsPerChild_) {
        stop();
    }
    if (pid_ == 0) {
        start();
        served_ = 0;
    }
    ++served_;
    if (!writeRequest(socket_, {file, expected, frames})) {
        // Gone since the last file (killed, out of memory): a new one gets this file.
        howItEnded();
        start();
        served_ = 1;
        if (!writeRequest(socket_, {file, expected, frames})) {
            throw LoadError(file + ": the frame decoder " + howItEnded() + " before it was asked");
        }
    }
    pollfd ready{socket_, POLLIN, 0};
    int n = 0;
    while ((n = ::poll(&ready, 1, static_cast<int>(timeout_.count()))) < 0 && errno == EINTR) {
    }
    if (n == 0) {
        stop();
        throw LoadError(file + ": decoding took longer than " +
                        std::to_string(timeout_.count() / 1000) + " s; stopped");
    }
    // The most a codec may return: every frame at 8 bytes a sample.
    const std::size_t most = static_cast<std::size_t>(expected.rows) * expected.columns *
                             static_cast<std::size_t>(frames) * 8 *
                             static_cast<std::size_t>(expected.samplesPerPixel);
    const std::optional<DecodeReply> reply = readReply(socket_, most);
    if (!reply) {
        throw LoadError(file + ": the frame decoder " + howItEnded() +
                        " on this file (damaged compressed pixel data)");
    }
    if (const auto* why = std::get_if<std::string>(&*reply)) {
        throw LoadError(*why);
    }
    return std::get<DecodedFrames>(*reply);
}

DecoderProcess& threadDecoderProcess() {
    thread_local DecoderProcess process;
    return process;
}

} // namespace lucent
