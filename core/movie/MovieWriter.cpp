#include "core/movie/MovieWriter.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <ostream>

#include "core/formats/AtomicFile.h"
#include "core/movie/PaletteQuantizer.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/log.h>
#include <libavutil/mem.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace lucent {
namespace {

std::string averror(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    return text;
}

// Owners of FFmpeg's objects, each freed by its own function.
struct FormatFree {
    void operator()(AVFormatContext* c) const { avformat_free_context(c); }
};
struct CodecFree {
    void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FrameFree {
    void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct PacketFree {
    void operator()(AVPacket* p) const { av_packet_free(&p); }
};
struct ScaleFree {
    void operator()(SwsContext* s) const { sws_freeContext(s); }
};
struct IoFree {
    void operator()(AVIOContext* io) const {
        av_freep(&io->buffer);
        avio_context_free(&io);
    }
};

// The muxers write through the atomic file's stream; MP4 seeks back to patch sizes.
int writePacket(void* opaque, std::uint8_t* data, int size) {
    std::ostream& out = *static_cast<std::ostream*>(opaque);
    out.write(reinterpret_cast<const char*>(data), size);
    return out ? size : AVERROR(EIO);
}

std::int64_t seekStream(void* opaque, std::int64_t offset, int whence) {
    std::ostream& out = *static_cast<std::ostream*>(opaque);
    if (whence & AVSEEK_SIZE) {
        const std::streampos here = out.tellp();
        out.seekp(0, std::ios::end);
        const std::streampos size = out.tellp();
        out.seekp(here);
        return out ? std::int64_t(size) : AVERROR(EIO);
    }
    const std::ios::seekdir dir = (whence & 0xff) == SEEK_CUR   ? std::ios::cur
                                  : (whence & 0xff) == SEEK_END ? std::ios::end
                                                                : std::ios::beg;
    out.seekp(offset, dir);
    return out ? std::int64_t(out.tellp()) : AVERROR(EIO);
}

struct FormatChoice {
    const char* muxer;
    const char* encoder;
    AVPixelFormat pixels;
};

FormatChoice choiceOf(MovieFormat format) {
    switch (format) {
    case MovieFormat::Mp4:
        return {"mp4", "libx264", AV_PIX_FMT_YUV420P};
    case MovieFormat::WebM:
        return {"webm", "libvpx-vp9", AV_PIX_FMT_YUV420P};
    case MovieFormat::Gif:
        break;
    }
    return {"gif", "gif", AV_PIX_FMT_PAL8};
}

// Quality settings: near-transparent for the image sizes a workstation exports.
void setEncoderOptions(MovieFormat format, AVCodecContext& codec) {
    if (format == MovieFormat::Mp4) {
        av_opt_set(codec.priv_data, "preset", "medium", 0);
        av_opt_set(codec.priv_data, "crf", "17", 0);
    } else if (format == MovieFormat::WebM) {
        codec.bit_rate = 0; // constant quality
        av_opt_set(codec.priv_data, "crf", "20", 0);
        av_opt_set(codec.priv_data, "deadline", "good", 0);
        av_opt_set(codec.priv_data, "cpu-used", "4", 0);
        av_opt_set(codec.priv_data, "row-mt", "1", 0);
    }
    if (format != MovieFormat::Gif) {
        // sRGB primaries with the BT.601 matrix and video range that swscale converts with.
        codec.color_range = AVCOL_RANGE_MPEG;
        codec.colorspace = AVCOL_SPC_SMPTE170M;
        codec.color_primaries = AVCOL_PRI_BT709;
        codec.color_trc = AVCOL_TRC_IEC61966_2_1;
    }
}

} // namespace

MovieFormat movieFormatOf(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".mp4") {
        return MovieFormat::Mp4;
    }
    if (ext == ".webm") {
        return MovieFormat::WebM;
    }
    if (ext == ".gif") {
        return MovieFormat::Gif;
    }
    throw MovieError(path.string() + ": unknown movie format '" + ext +
                     "' (write .mp4, .webm or .gif)");
}

const char* movieFormatName(MovieFormat format) {
    return choiceOf(format).muxer;
}

struct MovieWriter::Encoder {
    std::filesystem::path path;
    MovieFormat format = MovieFormat::Mp4;
    MovieSettings settings;
    formats::AtomicFileWriter file;
    std::unique_ptr<AVIOContext, IoFree> io;
    std::unique_ptr<AVFormatContext, FormatFree> container;
    std::unique_ptr<AVCodecContext, CodecFree> codec;
    AVStream* stream = nullptr; // owned by the container
    std::unique_ptr<AVFrame, FrameFree> frame;
    std::unique_ptr<AVPacket, PacketFree> packet;
    std::unique_ptr<SwsContext, ScaleFree> scale;
    int frames = 0;
    bool finished = false;

    Encoder(const std::filesystem::path& target, MovieFormat f, const MovieSettings& s)
        : path(target), format(f), settings(s), file(openFile(target)) {}

    static formats::AtomicFileWriter openFile(const std::filesystem::path& target) {
        try {
            return formats::AtomicFileWriter(target);
        } catch (const std::exception&) {
            const std::filesystem::path dir =
                target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
            throw MovieError(target.string() + ": cannot write a file in " + dir.string() +
                             " (missing or not writable)");
        }
    }

    [[noreturn]] void fail(const std::string& what, int code) const {
        throw MovieError(path.string() + ": " + what + ": " + averror(code));
    }

    void open() {
        // The encoders' banners and statistics are FFmpeg's info level; keep warnings.
        if (av_log_get_level() > AV_LOG_WARNING) {
            av_log_set_level(AV_LOG_WARNING);
        }
        const FormatChoice choice = choiceOf(format);
        const AVCodec* encoder = avcodec_find_encoder_by_name(choice.encoder);
        if (!encoder) {
            throw MovieError(path.string() + ": this FFmpeg has no " + choice.encoder +
                             " encoder (Debian's libavcodec59 has it)");
        }
        AVFormatContext* raw = nullptr;
        int rc = avformat_alloc_output_context2(&raw, nullptr, choice.muxer, nullptr);
        if (rc < 0 || !raw) {
            fail(std::string("no ") + choice.muxer + " muxer", rc);
        }
        container.reset(raw);
        codec.reset(avcodec_alloc_context3(encoder));
        stream = avformat_new_stream(container.get(), nullptr);
        frame.reset(av_frame_alloc());
        packet.reset(av_packet_alloc());
        if (!codec || !stream || !frame || !packet) {
            fail("allocating the encoder", AVERROR(ENOMEM));
        }
        codec->width = settings.width;
        codec->height = settings.height;
        codec->pix_fmt = choice.pixels;
        codec->time_base = AVRational{1, settings.framesPerSecond};
        codec->framerate = AVRational{settings.framesPerSecond, 1};
        codec->gop_size = std::max(1, settings.framesPerSecond * 2);
        if (container->oformat->flags & AVFMT_GLOBALHEADER) {
            codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
        }
        setEncoderOptions(format, *codec);
        if ((rc = avcodec_open2(codec.get(), encoder, nullptr)) < 0) {
            fail(std::string("cannot open the ") + choice.encoder + " encoder", rc);
        }
        if ((rc = avcodec_parameters_from_context(stream->codecpar, codec.get())) < 0) {
            fail("stream parameters", rc);
        }
        stream->time_base = codec->time_base;

        constexpr int kBufferSize = 1 << 16;
        auto* buffer = static_cast<unsigned char*>(av_malloc(kBufferSize));
        AVIOContext* ioRaw = buffer ? avio_alloc_context(buffer, kBufferSize, 1, &file.stream(),
                                                         nullptr, writePacket, seekStream)
                                    : nullptr;
        if (!ioRaw) {
            av_free(buffer);
            fail("allocating the output", AVERROR(ENOMEM));
        }
        io.reset(ioRaw);
        container->pb = io.get();
        container->flags |= AVFMT_FLAG_CUSTOM_IO;
        if ((rc = avformat_write_header(container.get(), nullptr)) < 0) {
            fail("writing the header", rc);
        }

        frame->format = choice.pixels;
        frame->width = settings.width;
        frame->height = settings.height;
        if ((rc = av_frame_get_buffer(frame.get(), 0)) < 0) {
            fail("allocating a frame", rc);
        }
        if (choice.pixels == AV_PIX_FMT_YUV420P) {
            scale.reset(sws_getContext(settings.width, settings.height, AV_PIX_FMT_RGBA,
                                       settings.width, settings.height, AV_PIX_FMT_YUV420P,
                                       SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INP, nullptr,
                                       nullptr, nullptr));
            if (!scale) {
                fail("no RGB to YUV conversion", AVERROR(EINVAL));
            }
        }
    }

    void fill(const ImageRGBA8& image) {
        int rc = av_frame_make_writable(frame.get());
        if (rc < 0) {
            fail("frame buffer", rc);
        }
        if (scale) {
            const std::uint8_t* source[1] = {image.pixels.data()};
            const int stride[1] = {4 * image.width};
            sws_scale(scale.get(), source, stride, 0, image.height, frame->data, frame->linesize);
            return;
        }
        const PalettedImage paletted = quantizeToPalette(image);
        for (int y = 0; y < image.height; ++y) {
            std::memcpy(frame->data[0] + std::ptrdiff_t(y) * frame->linesize[0],
                        paletted.indices.data() + std::size_t(y) * std::size_t(image.width),
                        std::size_t(image.width));
        }
        // PAL8: 256 native-endian 0xAARRGGBB entries, opaque; unused ones black.
        auto* palette = reinterpret_cast<std::uint32_t*>(frame->data[1]);
        for (std::size_t e = 0; e < 256; ++e) {
            const std::array<std::uint8_t, 3> c =
                e < paletted.palette.size() ? paletted.palette[e] : std::array<std::uint8_t, 3>{};
            palette[e] = 0xff000000u | std::uint32_t(c[0]) << 16 | std::uint32_t(c[1]) << 8 | c[2];
        }
    }

    // Sends a frame (null: the end) and writes every packet the encoder has ready.
    void encode(const AVFrame* input) {
        int rc = avcodec_send_frame(codec.get(), input);
        if (rc < 0) {
            fail("encoding", rc);
        }
        while ((rc = avcodec_receive_packet(codec.get(), packet.get())) >= 0) {
            if (packet->duration == 0) {
                packet->duration = 1; // one frame: MP4's edit list ends after the last one
            }
            av_packet_rescale_ts(packet.get(), codec->time_base, stream->time_base);
            packet->stream_index = stream->index;
            rc = av_interleaved_write_frame(container.get(), packet.get());
            if (rc < 0) {
                fail("writing a frame", rc);
            }
        }
        if (rc != AVERROR(EAGAIN) && rc != AVERROR_EOF) {
            fail("encoding", rc);
        }
    }
};

MovieWriter::MovieWriter(const std::filesystem::path& path, const MovieSettings& settings) {
    const MovieFormat format = movieFormatOf(path);
    if (settings.width < 2 || settings.height < 2 || settings.width > 8192 ||
        settings.height > 8192) {
        throw MovieError(path.string() + ": movie size " + std::to_string(settings.width) + "x" +
                         std::to_string(settings.height) + " is outside 2 to 8192 a side");
    }
    if (format != MovieFormat::Gif && (settings.width % 2 || settings.height % 2)) {
        throw MovieError(path.string() + ": " + movieFormatName(format) +
                         " needs an even width and height (4:2:0 colour), not " +
                         std::to_string(settings.width) + "x" + std::to_string(settings.height));
    }
    if (settings.framesPerSecond < 1 || settings.framesPerSecond > 120) {
        throw MovieError(path.string() + ": frame rate " +
                         std::to_string(settings.framesPerSecond) + " is outside 1 to 120");
    }
    encoder_ = std::make_unique<Encoder>(path, format, settings);
    encoder_->open();
}

// The encoder's members go in reverse order: FFmpeg's output before the atomic
// file, which removes the temporary file unless finish() renamed it.
MovieWriter::~MovieWriter() = default;

void MovieWriter::add(const ImageRGBA8& image) {
    Encoder& e = *encoder_;
    if (e.finished) {
        throw MovieError(e.path.string() + ": frame added after finish()");
    }
    if (image.width != e.settings.width || image.height != e.settings.height ||
        image.pixels.size() != 4 * image.pixelCount()) {
        throw MovieError(e.path.string() + ": frame of " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " in a movie of " +
                         std::to_string(e.settings.width) + "x" +
                         std::to_string(e.settings.height));
    }
    e.fill(image);
    e.frame->pts = e.frames;
    e.encode(e.frame.get());
    ++e.frames;
}

void MovieWriter::finish() {
    Encoder& e = *encoder_;
    if (e.frames == 0) {
        throw MovieError(e.path.string() + ": a movie needs at least one frame");
    }
    e.encode(nullptr);
    const int rc = av_write_trailer(e.container.get());
    if (rc < 0) {
        e.fail("writing the index", rc);
    }
    avio_flush(e.io.get());
    if (e.io->error < 0) {
        e.fail("writing", e.io->error);
    }
    e.file.commit();
    e.finished = true;
}

MovieFormat MovieWriter::format() const {
    return encoder_->format;
}

int MovieWriter::framesWritten() const {
    return encoder_->frames;
}

} // namespace lucent
