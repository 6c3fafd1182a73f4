// lucent-cli movie PATH -o OUT.(mp4|webm|gif) [--turntable DEG | --cine-axis i|j|k]
// [--frames N] [--fps N] [--window C,W|NAME] [render options], or --replay RECORDING
// [--replay-pace original|step]: a turntable of the volume rendering, a cine through
// the slices or a recorded teaching session, encoded with FFmpeg (core/movie).
#include <QCommandLineParser>
#include <QTextStream>

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include "CliCommand.h"
#include "RenderFlags.h"
#include "ReplayFrames.h"
#include "TerminalProgress.h"
#include "core/io/Catalog.h"
#include "core/movie/MovieFrames.h"
#include "core/movie/MovieWriter.h"
#include "core/mpr/WindowPresets.h"
#include "render/GlError.h"
#include "render/RenderDevice.h"

namespace lucent::cli {
namespace {

constexpr int kDefaultTurntableFrames = 72; // 5 degrees a frame for a full turn

// What the command line asks for, checked before anything is loaded.
struct MovieRequest {
    bool cine = false;
    IndexAxis axis = IndexAxis::K;
    double degrees = 360.0;
    int frames = 0; // 0: the default of the kind
    MovieSettings settings;
    RendererKind backend = RendererKind::Cpu;
    std::optional<remote::Recording> replay;
    remote::ReplayPace pace = remote::ReplayPace::Original;
};

// --replay: the recording's pace and its checks; the view comes from the recording.
void replayRequest(const QCommandLineParser& p, MovieRequest& r) {
    if (!p.isSet("replay")) {
        if (p.isSet("replay-pace")) {
            throw UsageError("--replay-pace is for --replay");
        }
        return;
    }
    for (const char* other :
         {"turntable", "cine-axis", "frames", "preset", "tf", "window", "series"}) {
        if (p.isSet(other)) {
            throw UsageError(std::string("--") + other +
                             " is not for --replay: the recording holds the series and its views");
        }
    }
    const QString pace = p.value("replay-pace");
    if (pace != "original" && pace != "step") {
        throw UsageError("--replay-pace must be original or step, not '" + pace.toStdString() +
                         "'");
    }
    r.pace = pace == "step" ? remote::ReplayPace::Step : remote::ReplayPace::Original;
}

// The recording's series in PATH: the id it was recorded under, or a clear refusal.
Volume loadRecordedSeries(const QString& path, const QString& recordingFile,
                          const remote::Recording& recording, const LoadControl& control) {
    const Catalog catalog = scanPath(path.toStdString(), control);
    for (const SeriesEntry& entry : catalog.series) {
        if (entry.id == recording.header.series) {
            return loadSeries(entry, control);
        }
    }
    throw std::runtime_error(recordingFile.toStdString() + " records series " +
                             recording.header.series + ", which " + path.toStdString() +
                             " does not hold");
}

MovieRequest requestOf(const QCommandLineParser& p) {
    MovieRequest r;
    if (p.isSet("turntable") && p.isSet("cine-axis")) {
        throw UsageError("--turntable and --cine-axis exclude each other");
    }
    r.cine = p.isSet("cine-axis");
    if (r.cine) {
        try {
            r.axis = parseIndexAxis(p.value("cine-axis").toStdString());
        } catch (const std::invalid_argument& e) {
            throw UsageError(std::string("--cine-axis: ") + e.what());
        }
        for (const char* renderOnly : {"turntable", "preset", "tf"}) {
            if (p.isSet(renderOnly)) {
                throw UsageError(std::string("--") + renderOnly + " is for turntables, not cines");
            }
        }
    } else if (p.isSet("window")) {
        throw UsageError("--window is for cines (--cine-axis)");
    }
    replayRequest(p, r);
    r.degrees = numberFlag(p, "turntable", 360.0);
    if (!std::isfinite(r.degrees)) {
        throw UsageError("--turntable must be a number of degrees");
    }
    const double frames = numberFlag(p, "frames", 0.0);
    if (p.isSet("frames") && (frames < 1 || frames > 100000 || frames != std::floor(frames))) {
        throw UsageError("--frames must be a whole number from 1 to 100000");
    }
    r.frames = int(frames);
    const double fps = numberFlag(p, "fps", 25.0);
    if (fps < 1 || fps > 120 || fps != std::floor(fps)) {
        throw UsageError("--fps must be a whole number from 1 to 120");
    }
    r.settings.framesPerSecond = int(fps);
    RenderDescription size; // --size, through the render options table
    applyRenderFlags(p, size);
    r.settings.width = size.width;
    r.settings.height = size.height;
    try {
        r.backend = parseRendererKind(p.value("backend").toStdString());
    } catch (const std::invalid_argument&) {
        throw UsageError("--backend must be cpu or gl, not '" + p.value("backend").toStdString() +
                         "'");
    }
    return r;
}

// --window CENTER,WIDTH or a preset's name; the MPR views' default otherwise.
WindowLevel windowOf(const QCommandLineParser& p, const Volume& volume) {
    WindowLevel window = defaultWindow(volume);
    if (!p.isSet("window")) {
        return window;
    }
    const QString text = p.value("window");
    for (const WindowPreset& preset : windowPresets()) {
        if (text.compare(QString::fromUtf8(preset.name.data(), qsizetype(preset.name.size())),
                         Qt::CaseInsensitive) == 0) {
            window.center = preset.center;
            window.width = preset.width;
            return window;
        }
    }
    const QStringList parts = text.split(',');
    bool centreOk = false, widthOk = false;
    if (parts.size() == 2) {
        window.center = parts[0].toDouble(&centreOk);
        window.width = parts[1].toDouble(&widthOk);
    }
    if (!centreOk || !widthOk || !(window.width > 0.0)) {
        throw UsageError("--window must be CENTER,WIDTH (width above 0) or a preset name, not '" +
                         text.toStdString() + "'");
    }
    return window;
}

void addMovieOptions(QCommandLineParser& parser) {
    parser.setApplicationDescription(
        "Writes a movie: a turntable of the volume rendering (the default: a full turn), or a "
        "cine through the slices along an index axis. MP4 (H.264), WebM (VP9) or GIF, by the "
        "output's extension. The movie appears whole or not at all.");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    parser.addOptions({
        {{"o", "output"}, "The movie to write: .mp4, .webm or .gif.", "OUT"},
        {"series", "Series id or UID (default: the largest volume).", "UID"},
        {"turntable",
         "Turn the camera's azimuth by DEG over the frames, from the render options' camera "
         "(default 360).",
         "DEG"},
        {"cine-axis", "A cine through the slices along the volume's index axis i, j or k.", "AXIS"},
        {"frames",
         "Number of frames (turntable: default 72; cine: default every slice, else spread "
         "evenly from the first slice to the last).",
         "N"},
        {"fps", "Frames per second (default 25).", "N"},
        {"window",
         "Cine window: CENTER,WIDTH or a CT preset (brain, lung, bone, ...; any case); default as "
         "the MPR "
         "views (CT soft tissue, else the 1st to 99th percentile).",
         "W"},
        {"backend", "Turntable renderer: cpu, or gl (an EGL context; the CPU where none).", "NAME",
         "cpu"},
        {"preset", "Transfer function preset (default ct-bone, ct-mip or mr-default).", "NAME"},
        {"tf", "Transfer function JSON file.", "FILE.json"},
        {"replay",
         "A recorded teaching session (lucent-server's DIR/recordings/ID.jsonl) of the series in "
         "PATH: its views, rendered here (size: the recording's unless --size).",
         "RECORDING"},
        {"replay-pace",
         "original: frame k shows the view current k/fps seconds into the recording (the "
         "default); step: one frame per recorded view.",
         "PACE", "original"},
    });
    addRenderFlags(parser);
    parser.addHelpOption();
}

// What makes the frames, and what it needs kept alive while they are made
// (frames last: they go first).
struct MovieSource {
    std::unique_ptr<RenderDevice> device;
    std::unique_ptr<Renderer> renderer;
    std::unique_ptr<MovieFrames> frames;
};

// A cine of the volume's slices, or frames rendered from it (a turntable, or
// a recording's views), on the requested backend where it opens.
MovieSource sourceOf(const QCommandLineParser& parser, MovieRequest& request, const Volume& volume,
                     QTextStream& err) {
    MovieSource source;
    if (request.cine) {
        source.frames = std::make_unique<CineFrames>(
            volume, request.axis, request.frames, windowOf(parser, volume), request.settings.width,
            request.settings.height);
        return source;
    }
    source.device = RenderDevice::open(request.backend);
    RenderDevice::Opened opened = source.device->openRenderer(volume);
    for (const std::string& reason : {source.device->fallbackReason(), opened.fallbackReason}) {
        if (!reason.empty()) {
            err << "lucent-cli movie: " << QString::fromStdString(reason)
                << "; rendering on the CPU instead\n";
        }
    }
    source.renderer = std::move(opened.renderer);
    if (request.replay) {
        source.frames = std::make_unique<ReplayFrames>(
            *source.renderer, volume, std::move(*request.replay), request.pace,
            request.settings.framesPerSecond, request.settings.width, request.settings.height);
    } else {
        RenderDescription start = describeFromFlags(parser, volume);
        start.validate();
        source.frames = std::make_unique<TurntableFrames>(
            *source.renderer, start, request.degrees,
            request.frames > 0 ? request.frames : kDefaultTurntableFrames);
    }
    return source;
}

} // namespace

int runMovie(const QStringList& args) {
    QCommandLineParser parser;
    addMovieOptions(parser);
    QTextStream err(stderr);
    if (!parser.parse(args)) {
        err << "lucent-cli movie: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        QTextStream(stdout) << parser.helpText();
        return kOk;
    }
    if (parser.positionalArguments().size() != 1 || !parser.isSet("output")) {
        err << "lucent-cli movie: expected PATH and -o OUT.mp4|OUT.webm|OUT.gif\n";
        return kUsage;
    }
    // The table's overlay rows come with the render flags; a movie has no --overlay yet.
    for (const char* flag : {"overlay-map", "overlay-window", "overlay-opacity"}) {
        if (parser.isSet(flag)) {
            err << "lucent-cli movie: --" << flag
                << ": movies draw no overlay (lucent-cli render --overlay does)\n";
            return kUsage;
        }
    }
    const std::string output = parser.value("output").toStdString();
    MovieRequest request;
    try {
        request = requestOf(parser);
        movieFormatOf(output);
    } catch (const std::exception& e) { // UsageError, MovieError, std::invalid_argument
        err << "lucent-cli movie: " << e.what() << "\n";
        return kUsage;
    }
    if (parser.isSet("replay")) {
        try {
            request.replay = remote::readRecording(parser.value("replay").toStdString());
        } catch (const remote::RecordingError& e) {
            err << "lucent-cli movie: " << e.what() << "\n";
            return kBadInput;
        }
        if (!parser.isSet("size")) {
            request.settings.width = request.replay->header.width;
            request.settings.height = request.replay->header.height;
        }
    }

    const TerminalProgress progress;
    try {
        // Opened first: an output that cannot be written fails before loading and rendering.
        MovieWriter writer(output, request.settings);
        const QString path = parser.positionalArguments()[0];
        const Volume volume =
            request.replay ? loadRecordedSeries(path, parser.value("replay"), *request.replay,
                                                progress.control())
                           : loadPath(path.toStdString(), parser.value("series").toStdString(),
                                      progress.control());
        progress.finish();
        const MovieSource source = sourceOf(parser, request, volume, err);
        writeMovie(*source.frames, writer, [&](int done, int total) {
            if (progress.control().onProgress) {
                progress.control().onProgress({"frame", std::size_t(done), std::size_t(total)});
            }
            return true;
        });
        progress.finish();
        QTextStream(stdout) << "wrote " << QString::fromStdString(output) << ": "
                            << writer.framesWritten() << " frames " << request.settings.width << "x"
                            << request.settings.height << " " << movieFormatName(writer.format())
                            << " at " << request.settings.framesPerSecond << " fps\n";
    } catch (const UsageError& e) {
        progress.finish();
        err << "lucent-cli movie: " << e.what() << "\n";
        return kUsage;
    } catch (const std::invalid_argument& e) {
        progress.finish();
        err << "lucent-cli movie: " << e.what() << "\n";
        return kUsage;
    } catch (const GlError& e) {
        progress.finish();
        err << "lucent-cli movie: GL: " << e.what() << "\n";
        return kBadInput;
    } catch (const std::exception& e) {
        progress.finish();
        err << "lucent-cli movie: " << e.what() << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
