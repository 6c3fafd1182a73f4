#include "core/dicom/SeriesLoader.h"

#include <cmath>
#include <map>
#include <optional>

#include "core/dicom/FirstDecodeError_p.h"
#include "core/dicom/FrameDecoder.h"
#include "core/dicom/PixelConversion.h"
#include "core/dicom/ProgressReporter.h"
#include "core/dicom/StackGeometry.h"
#include "core/dicom/StackResampler.h"

namespace lucent {
namespace {

// The plan again, from the entry: the scanner already sorted and de-duplicated
// the slices, so this only recomputes the grid placement for resampling.
StackPlan replan(const SeriesEntry& e) {
    StackInput in;
    in.rowDir = e.geometry.direction[0];
    in.colDir = e.geometry.direction[1];
    in.pixelSpacing = {e.geometry.spacing.x, e.geometry.spacing.y};
    in.columns = e.pixels.columns;
    in.rows = e.pixels.rows;
    for (const SliceRef& s : e.slices) {
        in.positions.push_back(s.position);
    }
    return planStack(in);
}

template <class Out>
void decodeInto(const SeriesEntry& e, Volume& stack, const LoadControl& control) {
    const std::size_t pixels = std::size_t(e.pixels.rows) * e.pixels.columns;
    const RawFormat headerFormat = rawFormatOf(e.pixels);
    const std::size_t frameBytes = pixels * static_cast<std::size_t>(e.pixels.bitsAllocated / 8);
    std::span<Out> out = stack.voxels<Out>();

    // One work item per file, so a multi-frame file is decoded once.
    std::map<std::string, std::vector<int>> byFile;
    for (std::size_t k = 0; k < e.slices.size(); ++k) {
        byFile[e.slices[k].file].push_back(static_cast<int>(k));
    }
    const std::vector<std::pair<std::string, std::vector<int>>> work(byFile.begin(), byFile.end());
    ProgressReporter progress(control, "decoding", work.size());
    FirstDecodeError error;

    const int count = static_cast<int>(work.size());
#pragma omp parallel num_threads(workerThreads(control))
    {
        std::vector<char> raw(frameBytes);
#pragma omp for schedule(dynamic, 4)
        for (int w = 0; w < count; ++w) {
            if (control.stopRequested()) {
                continue;
            }
            const auto& [file, ks] = work[w];
            try {
                const bool native = std::all_of(
                    ks.begin(), ks.end(), [&](int k) { return e.slices[k].pixelOffset != 0; });
                std::optional<DecodedFrames> decoded;
                if (!native) {
                    int frames = 0;
                    for (const int k : ks) {
                        frames = std::max(frames, e.slices[k].frame + 1);
                    }
                    decoded = decodeFrames(file, e.pixels, frames);
                }
                for (const int k : ks) {
                    const SliceRef& s = e.slices[k];
                    const char* src = nullptr;
                    RawFormat fmt = headerFormat;
                    if (native) {
                        readNativeFrame(file, s.pixelOffset, frameBytes, raw.data());
                        src = raw.data();
                    } else {
                        if (std::size_t(s.frame + 1) * decoded->frameBytes >
                            decoded->buffer.size()) {
                            throw LoadError(file + ": frame " + std::to_string(s.frame + 1) +
                                            " is missing from the decoded pixel data");
                        }
                        src = decoded->frame(s.frame);
                        fmt = decoded->format;
                    }
                    convertFrame(src, pixels, fmt, s.slope, s.intercept,
                                 out.data() + pixels * static_cast<std::size_t>(k));
                }
            } catch (const std::exception& ex) {
                error.record(file, ex);
            }
            progress.step();
        }
    }
    error.throwIfAny(control);
}

// Float volumes whose values are all integers that fit int16 become int16:
// 16-bit stored CT with an integer rescale lands here.
Volume narrowIfExact(Volume v, const SeriesEntry& e) {
    if (v.type() != VoxelType::Float32) {
        return v;
    }
    for (const SliceRef& s : e.slices) {
        if (s.slope != std::round(s.slope) || s.intercept != std::round(s.intercept)) {
            return v;
        }
    }
    const auto [lo, hi] = v.valueRange();
    if (lo < -32768.0 || hi > 32767.0) {
        return v;
    }
    Volume narrow(v.geometry(), VoxelType::Int16);
    const auto src = v.voxels<float>();
    const auto dst = narrow.voxels<std::int16_t>();
    for (std::size_t i = 0; i < src.size(); ++i) {
        dst[i] = static_cast<std::int16_t>(src[i]);
    }
    return narrow;
}

} // namespace

Volume loadDicomSeries(const SeriesEntry& e, const LoadControl& control) {
    if (e.slices.empty()) {
        throw LoadError("series " + e.id + " has no images to load");
    }
    std::optional<StackPlan> plan;
    VolumeGeometry stackGeometry = e.geometry;
    if (e.resampled) {
        plan = replan(e);
        stackGeometry.dims = {e.pixels.columns, e.pixels.rows, static_cast<int>(e.slices.size())};
    }
    Volume stack(stackGeometry, e.voxelType);
    visitVoxels(stack, [&](auto voxels) {
        using T = std::remove_const_t<typename decltype(voxels)::element_type>;
        decodeInto<T>(e, stack, control);
    });

    Volume volume;
    if (plan) {
        if (control.onProgress) {
            control.onProgress({"resampling", 0, 1});
        }
        const double pad = stack.valueRange().first;
        volume = resampleStack(stack, *plan, pad);
        volume.setGeometry(e.geometry);
    } else {
        volume = std::move(stack);
    }
    volume = narrowIfExact(std::move(volume), e);
    static_cast<SeriesInfo&>(volume) = e;
    volume.warnings = e.warnings;
    return volume;
}

} // namespace lucent
