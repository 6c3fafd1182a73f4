#pragma once
// A movie file from RGB frames, encoded with FFmpeg's libraries (kept private):
// H.264 in MP4, VP9 in WebM, or an animated GIF, chosen by the file's extension.
// The file appears complete or not at all: frames go to a temporary file beside
// it, renamed into place by finish(); a writer destroyed before finish() (an
// error, a cancel) removes it.

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/image/Image.h"

namespace lucent {

enum class MovieFormat { Mp4, WebM, Gif };

// A movie the writer cannot make (format, size, output place); the message
// names the file or the setting.
class MovieError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The format of `path` from its extension (.mp4, .webm, .gif; any case).
// Throws MovieError naming the file and the extensions it knows.
MovieFormat movieFormatOf(const std::filesystem::path& path);
// "mp4", "webm", "gif".
const char* movieFormatName(MovieFormat format);

struct MovieSettings {
    int width = 512;
    int height = 512;
    int framesPerSecond = 25; // 1 to 120
};

class MovieWriter {
public:
    // Checks the format and size and opens the temporary file beside `path`, so
    // that a movie that cannot be written fails before any frame is rendered.
    // Throws MovieError naming the file (unknown extension, a directory that
    // cannot be written) or the size (MP4 and WebM need even sides).
    MovieWriter(const std::filesystem::path& path, const MovieSettings& settings);
    ~MovieWriter(); // without finish(): removes the temporary file
    MovieWriter(const MovieWriter&) = delete;
    MovieWriter& operator=(const MovieWriter&) = delete;

    // Encodes one frame of the settings' size (its alpha is ignored).
    // Throws MovieError on a size mismatch or an encoder failure.
    void add(const ImageRGBA8& frame);
    // Flushes the encoder, writes the container's index and renames the file
    // into place. Throws MovieError when there is no frame or a write failed.
    void finish();

    MovieFormat format() const;
    int framesWritten() const;

private:
    struct Encoder;
    std::unique_ptr<Encoder> encoder_;
};

} // namespace lucent
