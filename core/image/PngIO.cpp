#include "core/image/PngIO.h"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "core/formats/AtomicFile.h"
#include "core/io/LoadControl.h"

// libpng reports errors with longjmp. Every setjmp below sits in a function
// that owns no object with a destructor, and the error callback builds no
// such object either, so a longjmp never skips a destructor. The libpng
// structs, the file and the buffers belong to RAII owners in the callers.

namespace lucent {

namespace {

// Where the error callback leaves libpng's message: plain storage, no
// destructor to skip.
struct PngError {
    char message[256] = {};
};

[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
    auto* error = static_cast<PngError*>(png_get_error_ptr(png));
    if (error != nullptr) {
        std::snprintf(error->message, sizeof error->message, "%s",
                      message != nullptr ? message : "unknown libpng error");
    }
    png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {
    // Warnings (an unknown chunk, a questionable profile) do not stop the read.
}

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

struct ReadStructs {
    png_structp png = nullptr;
    png_infop info = nullptr;
    ReadStructs(const ReadStructs&) = delete;
    ReadStructs& operator=(const ReadStructs&) = delete;
    explicit ReadStructs(PngError& error) {
        png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, onPngError, onPngWarning);
        if (png != nullptr) {
            info = png_create_info_struct(png);
        }
    }
    ~ReadStructs() { png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr); }
};

struct WriteStructs {
    png_structp png = nullptr;
    png_infop info = nullptr;
    WriteStructs(const WriteStructs&) = delete;
    WriteStructs& operator=(const WriteStructs&) = delete;
    explicit WriteStructs(PngError& error) {
        png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, onPngError, onPngWarning);
        if (png != nullptr) {
            info = png_create_info_struct(png);
        }
    }
    ~WriteStructs() { png_destroy_write_struct(&png, info != nullptr ? &info : nullptr); }
};

// Reads the header, sets the transforms that turn any PNG into 8-bit RGBA and
// returns false (message in the error pointer) if libpng fails.
bool readHeader(png_structp png, png_infop info, std::FILE* file, png_uint_32& width,
                png_uint_32& height) {
    if (setjmp(png_jmpbuf(png))) {
        return false;
    }
    png_init_io(png, file);
    png_set_sig_bytes(png, 8);
    png_set_user_limits(png, kMaxPngSide, kMaxPngSide);
    png_read_info(png, info);
    const png_byte colorType = png_get_color_type(png, info);
    png_set_expand(png); // palette -> RGB, grey < 8 bits -> 8 bits, tRNS -> alpha
    png_set_scale_16(png);
    if (colorType == PNG_COLOR_TYPE_GRAY || colorType == PNG_COLOR_TYPE_GRAY_ALPHA) {
        png_set_gray_to_rgb(png);
    }
    if ((colorType & PNG_COLOR_MASK_ALPHA) == 0 && !png_get_valid(png, info, PNG_INFO_tRNS)) {
        png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    }
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    width = png_get_image_width(png, info);
    height = png_get_image_height(png, info);
    if (png_get_rowbytes(png, info) != 4 * static_cast<std::size_t>(width)) {
        png_error(png, "unexpected row size after conversion to RGBA8");
    }
    return true;
}

bool readRows(png_structp png, png_infop info, png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) {
        return false;
    }
    png_read_image(png, rows);
    png_read_end(png, info);
    return true;
}

void writeToStream(png_structp png, png_bytep data, png_size_t length) {
    auto* out = static_cast<std::ostream*>(png_get_io_ptr(png));
    out->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
    if (!*out) {
        png_error(png, "write failed (disk full or no permission?)");
    }
}

void flushStream(png_structp png) {
    static_cast<std::ostream*>(png_get_io_ptr(png))->flush();
}

bool writeAll(png_structp png, png_infop info, std::ostream* out, const ImageRGBA8& image,
              png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) {
        return false;
    }
    png_set_write_fn(png, out, writeToStream, flushStream);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, info);
    return true;
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& problem) {
    throw LoadError(file.string() + ": " + problem);
}

} // namespace

ImageRGBA8 readPng(const std::filesystem::path& file) {
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    if (!std::filesystem::exists(status)) {
        fail(file, "no such file");
    }
    if (std::filesystem::is_directory(status)) {
        fail(file, "is a folder, not a PNG file");
    }
    const FilePtr f(std::fopen(file.c_str(), "rb"));
    if (!f) {
        fail(file, std::string("cannot open: ") + std::strerror(errno));
    }
    png_byte signature[8] = {};
    const std::size_t got = std::fread(signature, 1, sizeof signature, f.get());
    if (got != sizeof signature || png_sig_cmp(signature, 0, sizeof signature) != 0) {
        if (std::ferror(f.get())) {
            fail(file, std::string("cannot read: ") + std::strerror(errno));
        }
        fail(file, "not a PNG file (no PNG signature)");
    }

    PngError error;
    ReadStructs s(error);
    if (s.png == nullptr || s.info == nullptr) {
        fail(file, "cannot set up the PNG reader (out of memory?)");
    }
    png_uint_32 width = 0;
    png_uint_32 height = 0;
    if (!readHeader(s.png, s.info, f.get(), width, height)) {
        fail(file, std::string("bad PNG header: ") + error.message);
    }
    if (width == 0 || height == 0) {
        fail(file, "bad PNG header: empty image");
    }
    ImageRGBA8 image = ImageRGBA8::filled(static_cast<int>(width), static_cast<int>(height));
    std::vector<png_bytep> rows(height);
    for (png_uint_32 y = 0; y < height; ++y) {
        rows[y] = image.at(0, static_cast<int>(y));
    }
    if (!readRows(s.png, s.info, rows.data())) {
        fail(file, std::string("corrupt or truncated PNG: ") + error.message);
    }
    return image;
}

void writePng(const ImageRGBA8& image, const std::filesystem::path& file) {
    if (image.width <= 0 || image.height <= 0) {
        throw std::runtime_error(file.string() + ": cannot write an empty image (" +
                                 std::to_string(image.width) + "x" + std::to_string(image.height) +
                                 ") as PNG");
    }
    if (image.pixels.size() != 4 * image.pixelCount()) {
        throw std::runtime_error(file.string() + ": image buffer holds " +
                                 std::to_string(image.pixels.size()) + " bytes, not " +
                                 std::to_string(4 * image.pixelCount()));
    }
    // libpng takes non-const row pointers but only reads them when writing.
    std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
    for (int y = 0; y < image.height; ++y) {
        rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(image.at(0, y));
    }
    PngError error;
    WriteStructs s(error);
    if (s.png == nullptr || s.info == nullptr) {
        throw std::runtime_error(file.string() + ": cannot set up the PNG writer (out of memory?)");
    }
    formats::AtomicFileWriter writer(file);
    if (!writeAll(s.png, s.info, &writer.stream(), image, rows.data())) {
        throw std::runtime_error(file.string() + ": cannot write PNG: " + error.message);
    }
    writer.commit();
}

} // namespace lucent
