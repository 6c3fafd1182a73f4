#include "core/dicom/SeriesScanner.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <set>

#include "core/dicom/ImageRecord.h"
#include "core/dicom/ProgressReporter.h"
#include "core/dicom/StackGeometry.h"

namespace lucent {
namespace {

// Images that can be stacked together: one series, one orientation, one size,
// one kind; for enhanced objects also one file and one frame type.
struct Group {
    std::vector<const ImageRecord*> images;
    const ImageRecord& first() const { return *images.front(); }
};

// Colour, palette colour and cine frames make 2D stacks (SeriesKind::Stack), not volumes.
bool isStackImage(const ImageRecord& r) {
    return r.pixels.samplesPerPixel != 1 || r.pixels.photometric == "PALETTE COLOR" || r.cine;
}

bool sameStack(const ImageRecord& a, const ImageRecord& b) {
    constexpr double kOrientationTolerance = 1e-3;
    if (isStackImage(a) != isStackImage(b) || a.pixels.photometric != b.pixels.photometric ||
        (a.cine && a.file != b.file)) {
        return false;
    }
    if (a.localizer != b.localizer || a.pixels.rows != b.pixels.rows ||
        a.pixels.columns != b.pixels.columns || a.hasPosition != b.hasPosition ||
        a.enhanced != b.enhanced) {
        return false;
    }
    if (a.enhanced && (a.file != b.file || a.imageType != b.imageType)) {
        return false;
    }
    if (glm::length(a.rowDir - b.rowDir) > kOrientationTolerance ||
        glm::length(a.colDir - b.colDir) > kOrientationTolerance) {
        return false;
    }
    return glm::length(a.pixelSpacing - b.pixelSpacing) <= 1e-4 * glm::length(a.pixelSpacing);
}

// The voxel type that holds every rescaled value of the entry exactly, if one does.
VoxelType chooseVoxelType(const std::vector<const ImageRecord*>& images) {
    double lo = std::numeric_limits<double>::max();
    double hi = std::numeric_limits<double>::lowest();
    bool integral = true;
    for (const ImageRecord* r : images) {
        const PixelLayout& p = r->pixels;
        const double rawLo = p.isSigned ? -std::ldexp(1.0, p.bitsStored - 1) : 0.0;
        const double rawHi =
            p.isSigned ? std::ldexp(1.0, p.bitsStored - 1) - 1 : std::ldexp(1.0, p.bitsStored) - 1;
        integral = integral && r->slope == std::round(r->slope) &&
                   r->intercept == std::round(r->intercept);
        for (const double raw : {rawLo, rawHi}) {
            const double v = raw * r->slope + r->intercept;
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    }
    if (integral && lo >= -32768.0 && hi <= 32767.0) {
        return VoxelType::Int16;
    }
    if (integral && lo >= 0.0 && hi <= 65535.0) {
        return VoxelType::UInt16;
    }
    return VoxelType::Float32;
}

// A warning's kind: its text with every number (a byte count, an offset) as '#'.
std::string warningKind(const std::string& text) {
    std::string kind;
    for (const char c : text) {
        const bool digit = c >= '0' && c <= '9';
        if (!digit) {
            kind += c;
        } else if (kind.empty() || kind.back() != '#') {
            kind += '#';
        }
    }
    return kind;
}

// The files' own warnings (ImageRecord::warnings), once per kind: the first
// file's text with that file, and how many files have one of the kind.
void appendFileWarnings(const Group& group, std::vector<std::string>& warnings) {
    struct Kind {
        std::string key, firstText, firstFile;
        std::set<std::string> files;
    };
    std::vector<Kind> kinds;
    for (const ImageRecord* r : group.images) {
        for (const std::string& w : r->warnings) {
            const std::string key = warningKind(w);
            auto it = std::find_if(kinds.begin(), kinds.end(),
                                   [&key](const Kind& k) { return k.key == key; });
            if (it == kinds.end()) {
                kinds.push_back({key, w, r->file, {}});
                it = kinds.end() - 1;
            }
            it->files.insert(r->file);
        }
    }
    for (const Kind& k : kinds) {
        warnings.push_back(k.files.size() == 1
                               ? k.firstFile + ": " + k.firstText
                               : k.firstText + " (and in " + std::to_string(k.files.size() - 1) +
                                     " more files; first: " + k.firstFile + ")");
    }
}

SeriesEntry makeEntry(const Group& group, SeriesKind kind, std::vector<SkippedFile>& skipped) {
    const ImageRecord& f = group.first();
    SeriesEntry e;
    static_cast<SeriesInfo&>(e) = f;
    e.kind = kind;
    e.format = SourceFormat::Dicom;
    e.pixels = f.pixels;
    e.voxelType = chooseVoxelType(group.images);
    e.seriesNumber = f.seriesNumber;
    e.sliceThickness = f.sliceThickness;
    e.studyDescription = f.studyDescription;
    e.studyTime = f.studyTime;
    e.bodyPart = f.bodyPart;
    if (!f.hasPixelSpacing) {
        e.warnings.push_back("no PixelSpacing: 1 mm assumed in the image plane");
    }
    if (!f.hasPosition) {
        e.warnings.push_back("no ImagePositionPatient/ImageOrientationPatient: the image grid "
                             "is shown without patient geometry");
    }

    appendFileWarnings(group, e.warnings);

    StackInput in;
    in.rowDir = f.rowDir;
    in.colDir = f.colDir;
    in.pixelSpacing = f.pixelSpacing;
    in.columns = f.pixels.columns;
    in.rows = f.pixels.rows;
    in.sliceThickness = f.sliceThickness;
    for (const ImageRecord* r : group.images) {
        in.positions.push_back(r->position);
    }
    StackPlan plan = planStack(in);
    if (!plan.error.empty()) {
        e.warnings.push_back(plan.error + "; only the first image is used");
        in.positions.resize(1);
        plan = planStack(in);
        e.kind = SeriesKind::Image;
    }
    if (!plan.dropped.empty()) {
        const ImageRecord& d = *group.images[plan.dropped.front()];
        e.warnings.push_back("dropped " + std::to_string(plan.dropped.size()) +
                             " image(s) at a position already taken (first: " + d.file +
                             (d.enhanced ? " frame " + std::to_string(d.frame + 1) : "") + ")");
        for (int i : plan.dropped) {
            const ImageRecord& r = *group.images[i];
            skipped.push_back({r.file, "duplicate position in series " + r.seriesUid});
        }
    }
    for (std::string& w : plan.warnings) {
        e.warnings.push_back(std::move(w));
    }
    e.geometry = plan.geometry;
    e.resampled = plan.resample;
    for (std::size_t s = 0; s < plan.order.size(); ++s) {
        const ImageRecord& r = *group.images[plan.order[s]];
        e.slices.push_back({r.file, r.frame, r.position, r.slope, r.intercept, r.pixelOffset});
    }
    if (e.kind == SeriesKind::Volume && e.slices.size() == 1) {
        e.kind = SeriesKind::Image;
    }
    e.hasPosition = f.hasPosition;
    e.hasPixelSpacing = f.hasPixelSpacing;
    return e;
}

// A 2D stack: its images in the order read (instance number, file, frame), each
// with its own position; the geometry is the first image's plane.
SeriesEntry makeStackEntry(const Group& group) {
    const ImageRecord& f = group.first();
    SeriesEntry e;
    static_cast<SeriesInfo&>(e) = f;
    e.kind = SeriesKind::Stack;
    e.format = SourceFormat::Dicom;
    e.pixels = f.pixels;
    e.hasPosition = f.hasPosition;
    e.hasPixelSpacing = f.hasPixelSpacing;
    appendFileWarnings(group, e.warnings);
    e.geometry.dims = {f.pixels.columns, f.pixels.rows, static_cast<int>(group.images.size())};
    e.geometry.spacing = {f.pixelSpacing.x, f.pixelSpacing.y, 1.0};
    e.geometry.origin = f.position;
    e.geometry.direction =
        glm::dmat3(f.rowDir, f.colDir, glm::normalize(glm::cross(f.rowDir, f.colDir)));
    for (const ImageRecord* r : group.images) {
        e.slices.push_back(
            {r->file, r->frame, r->position, r->slope, r->intercept, r->pixelOffset});
    }
    return e;
}

} // namespace

void scanDicomFiles(const std::vector<std::string>& files, Catalog& catalog,
                    const LoadControl& control) {
    std::vector<FileScan> scans(files.size());
    ProgressReporter progress(control, "scanning", files.size());
    const int count = static_cast<int>(files.size());
#pragma omp parallel for schedule(dynamic, 8) num_threads(workerThreads(control))
    for (int i = 0; i < count; ++i) {
        if (control.stopRequested()) {
            continue;
        }
        scans[i] = scanDicomFile(files[i]);
        progress.step();
    }
    if (control.stopRequested()) {
        throw LoadCancelled();
    }

    // Group by series, then split each series into stackable groups.
    std::map<std::string, std::vector<const ImageRecord*>> bySeries;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        if (scans[i].images.empty()) {
            catalog.skipped.push_back({files[i], scans[i].skipReason});
            continue;
        }
        for (const ImageRecord& r : scans[i].images) {
            bySeries[r.seriesUid].push_back(&r);
        }
    }
    struct Part {
        SeriesEntry entry;
        int seriesNumber;
    };
    std::vector<Part> parts;
    for (auto& [uid, images] : bySeries) {
        std::stable_sort(images.begin(), images.end(),
                         [](const ImageRecord* a, const ImageRecord* b) {
                             return std::tie(a->instanceNumber, a->file, a->frame) <
                                    std::tie(b->instanceNumber, b->file, b->frame);
                         });
        std::vector<Group> groups;
        for (const ImageRecord* r : images) {
            if (!r->hasPosition && !isStackImage(*r)) {
                groups.push_back({{r}}); // without a position an image cannot join a stack
                continue;
            }
            auto it = std::find_if(groups.begin(), groups.end(),
                                   [r](const Group& g) { return sameStack(g.first(), *r); });
            if (it == groups.end()) {
                groups.push_back({{r}});
            } else {
                it->images.push_back(r);
            }
        }
        // The main stack is the largest non-localizer group; other orientations are scouts.
        std::stable_sort(groups.begin(), groups.end(), [](const Group& a, const Group& b) {
            if (isStackImage(a.first()) != isStackImage(b.first())) {
                return !isStackImage(a.first());
            }
            if (a.first().localizer != b.first().localizer) {
                return !a.first().localizer;
            }
            return a.images.size() > b.images.size();
        });
        const ImageRecord& main = groups.front().first();
        int n = 0;
        for (const Group& g : groups) {
            const ImageRecord& f = g.first();
            const bool otherOrientation = &g != &groups.front() && !f.enhanced &&
                                          (glm::length(f.rowDir - main.rowDir) > 1e-3 ||
                                           glm::length(f.colDir - main.colDir) > 1e-3);
            SeriesKind kind = g.images.size() > 1 ? SeriesKind::Volume : SeriesKind::Image;
            if (f.localizer || otherOrientation) {
                kind = SeriesKind::Localizer;
            }
            SeriesEntry e =
                isStackImage(f) ? makeStackEntry(g) : makeEntry(g, kind, catalog.skipped);
            e.id = n == 0 ? uid : uid + "#" + std::to_string(n + 1);
            if (f.enhanced && !f.imageType.empty()) {
                e.description +=
                    (e.description.empty() ? "" : " ") + std::string("[") + f.imageType + "]";
            }
            parts.push_back({std::move(e), f.seriesNumber});
            ++n;
        }
    }
    std::stable_sort(parts.begin(), parts.end(),
                     [](const Part& a, const Part& b) { return a.seriesNumber < b.seriesNumber; });
    for (Part& p : parts) {
        catalog.series.push_back(std::move(p.entry));
    }
}

} // namespace lucent
