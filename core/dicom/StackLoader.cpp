#include "core/dicom/StackLoader.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <optional>

#include "core/dicom/ColourConversion_p.h"
#include "core/dicom/FirstDecodeError_p.h"
#include "core/dicom/FrameDecoder.h"
#include "core/dicom/PixelConversion.h"
#include "core/dicom/ProgressReporter.h"
#include "core/dicom/StackHeader_p.h"

namespace lucent {
namespace {

bool isPalette(const PixelLayout& px) {
    return px.samplesPerPixel == 1 && px.photometric == "PALETTE COLOR";
}

// A volume's slices as grey frames (other formats, and DICOM loaded by loadSeries).
ImageStack stackOfVolume(const Volume& v) {
    ImageStack s;
    static_cast<SeriesInfo&>(s) = v;
    const VolumeGeometry& g = v.geometry();
    s.columns = g.dims.x;
    s.rows = g.dims.y;
    s.photometric = "MONOCHROME2";
    s.warnings = v.warnings;
    s.grey.resize(g.voxelCount());
    for (int k = 0; k < g.dims.z; ++k) {
        StackFrame f;
        f.hasPosition = f.hasPixelSpacing = true;
        f.position = g.toPatient({0.0, 0.0, k});
        f.rowDir = g.direction[0];
        f.colDir = g.direction[1];
        f.pixelSpacing = {g.spacing.x, g.spacing.y};
        s.frames.push_back(f);
    }
    for (std::size_t i = 0; i < s.grey.size(); ++i) {
        const std::size_t slice = s.pixelCount();
        s.grey[i] = static_cast<float>(v.value(static_cast<int>(i % s.columns),
                                               static_cast<int>(i / s.columns % s.rows),
                                               static_cast<int>(i / slice)));
    }
    return s;
}

// The bytes of one frame as stored (uncompressed): YBR_FULL_422 is subsampled.
std::size_t storedFrameBytes(const PixelLayout& px) {
    const std::size_t pixels = static_cast<std::size_t>(px.rows) * px.columns;
    const auto bytes = static_cast<std::size_t>(px.bitsAllocated / 8);
    return px.photometric == "YBR_FULL_422"
               ? pixels * 2 * bytes
               : pixels * bytes * static_cast<std::size_t>(px.samplesPerPixel);
}

// Frame k's time from the first frame of its file: the FrameTimeVector's sum (its
// first value is 0), else frame times FrameTime.
double frameTime(const StackHeader& h, int frame) {
    if (h.frameTimeVector.size() > static_cast<std::size_t>(frame)) {
        return std::accumulate(h.frameTimeVector.begin() + 1, h.frameTimeVector.begin() + frame + 1,
                               0.0);
    }
    return h.frameTimeMs * frame;
}

// The nominal time between frames: FrameTime, else the vector's mean step.
double nominalFrameTime(const StackHeader& h) {
    if (h.frameTimeMs > 0.0) {
        return h.frameTimeMs;
    }
    if (h.frameTimeVector.size() > 1) {
        return std::accumulate(h.frameTimeVector.begin() + 1, h.frameTimeVector.end(), 0.0) /
               static_cast<double>(h.frameTimeVector.size() - 1);
    }
    return 0.0;
}

struct FileWork {
    std::string file;
    std::vector<int> slices; // indices into entry.slices
};

// Decodes the frames of one file into the stack and returns its header.
StackHeader decodeFile(const SeriesEntry& e, const FileWork& work, ImageStack& s) {
    const PixelLayout& px = e.pixels;
    StackHeader header = readStackHeader(work.file, isPalette(px));
    const bool native = std::all_of(work.slices.begin(), work.slices.end(),
                                    [&](int k) { return e.slices[k].pixelOffset != 0; });
    std::optional<DecodedFrames> decoded;
    std::vector<char> raw;
    if (native) {
        raw.resize(storedFrameBytes(px));
    } else {
        int frames = 0;
        for (const int k : work.slices) {
            frames = std::max(frames, e.slices[k].frame + 1);
        }
        decoded = decodeFrames(work.file, px, frames);
    }
    const std::size_t n = s.pixelCount();
    for (const int k : work.slices) {
        const SliceRef& ref = e.slices[k];
        const char* src = nullptr;
        RawFormat format = rawFormatOf(px);
        std::string photometric = px.photometric;
        int planar = px.planarConfiguration;
        if (native) {
            readNativeFrame(work.file, ref.pixelOffset, raw.size(), raw.data());
            src = raw.data();
        } else {
            if (std::size_t(ref.frame + 1) * decoded->frameBytes > decoded->buffer.size()) {
                throw LoadError(work.file + ": frame " + std::to_string(ref.frame + 1) +
                                " is missing from the decoded pixel data");
            }
            src = decoded->frame(ref.frame);
            format = decoded->format;
            if (px.samplesPerPixel == 3 && format.bitsAllocated != 8) {
                throw LoadError(work.file + ": the codec returned " +
                                std::to_string(format.bitsAllocated) +
                                "-bit colour samples, the header says 8");
            }
            photometric = px.samplesPerPixel == 3 ? decoded->photometric : px.photometric;
            planar = decoded->planarConfiguration;
        }
        const auto at = static_cast<std::size_t>(k);
        if (px.samplesPerPixel == 3) {
            colourFrameToRgb(work.file, src, s.columns, s.rows, photometric, planar,
                             s.rgb.data() + 3 * n * at);
        } else if (isPalette(px)) {
            paletteFrameToRgb(src, n, format, header.palette, s.rgb.data() + 3 * n * at);
        } else {
            convertFrame(src, n, format, ref.slope, ref.intercept, s.grey.data() + n * at);
        }
        s.frames[at].timeMs = frameTime(header, ref.frame);
    }
    return header;
}

ImageStack emptyStack(const SeriesEntry& e) {
    const PixelLayout& px = e.pixels;
    ImageStack s;
    static_cast<SeriesInfo&>(s) = e;
    s.columns = px.columns;
    s.rows = px.rows;
    s.photometric = px.photometric;
    s.inverted = px.samplesPerPixel == 1 && px.photometric == "MONOCHROME1";
    s.colour = px.samplesPerPixel == 3 || isPalette(px) ? StackColour::Rgb8 : StackColour::Grey;
    s.warnings = e.warnings;
    const std::size_t values = s.pixelCount() * e.slices.size();
    if (s.colour == StackColour::Rgb8) {
        s.rgb.resize(3 * values);
    } else {
        s.grey.resize(values);
    }
    for (const SliceRef& ref : e.slices) {
        StackFrame f;
        f.hasPosition = e.hasPosition;
        f.position = ref.position;
        f.rowDir = e.geometry.direction[0];
        f.colDir = e.geometry.direction[1];
        f.hasPixelSpacing = e.hasPixelSpacing;
        f.pixelSpacing = {e.geometry.spacing.x, e.geometry.spacing.y};
        s.frames.push_back(f);
    }
    return s;
}

} // namespace

ImageStack loadStack(const SeriesEntry& e, const LoadControl& control) {
    if (e.format != SourceFormat::Dicom) {
        return stackOfVolume(loadSeries(e, control));
    }
    if (e.slices.empty()) {
        throw LoadError("series " + e.id + " has no images to load");
    }
    ImageStack s = emptyStack(e);
    std::map<std::string, std::vector<int>> byFile;
    for (std::size_t k = 0; k < e.slices.size(); ++k) {
        byFile[e.slices[k].file].push_back(static_cast<int>(k));
    }
    std::vector<FileWork> work;
    for (auto& [file, slices] : byFile) {
        work.push_back({file, std::move(slices)});
    }
    std::vector<std::optional<StackHeader>> headers(work.size());
    ProgressReporter progress(control, "decoding", work.size());
    FirstDecodeError error;
    const int count = static_cast<int>(work.size());
#pragma omp parallel for schedule(dynamic, 4) num_threads(workerThreads(control))
    for (int w = 0; w < count; ++w) {
        if (control.stopRequested()) {
            continue;
        }
        try {
            headers[static_cast<std::size_t>(w)] =
                decodeFile(e, work[static_cast<std::size_t>(w)], s);
        } catch (const std::exception& ex) {
            error.record(work[static_cast<std::size_t>(w)].file, ex);
        }
        progress.step();
    }
    error.throwIfAny(control);
    // The first frame's file speaks for the stack (window, cine timing).
    const auto first = std::find_if(work.begin(), work.end(), [](const FileWork& f) {
        return std::find(f.slices.begin(), f.slices.end(), 0) != f.slices.end();
    });
    const StackHeader& h = *headers[static_cast<std::size_t>(first - work.begin())];
    s.window = h.window;
    s.frameTimeMs = nominalFrameTime(h);
    return s;
}

ImageStack loadStackPreview(const SeriesEntry& entry, const LoadControl& control) {
    if (entry.format != SourceFormat::Dicom || entry.slices.size() <= 1) {
        return loadStack(entry, control);
    }
    SeriesEntry one = entry;
    one.slices = {entry.slices[entry.slices.size() / 2]};
    return loadStack(one, control);
}

} // namespace lucent
