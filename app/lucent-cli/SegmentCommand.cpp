// lucent-cli segment PATH --threshold LO,HI [...] -o labels.nii.gz|seg.dcm [--stats]
// [--surface MESH]: a segment by threshold, islands and margin, written as a NIfTI labelmap or
// a DICOM SEG (and its surface as STL, PLY or OBJ); lucent-cli segment-stats PATH
// LABELS.nii[.gz]|SEG: the statistics of each label of a labelmap, or each segment of a DICOM
// SEG, on PATH's series.
#include <QCommandLineParser>
#include <QTextStream>

#include <cmath>
#include <cstdio>
#include <functional>

#include "CliCommand.h"
#include "core/formats/MeshFiles.h"
#include "core/formats/Nifti.h"
#include "core/formats/NiftiWrite.h"
#include "core/io/Catalog.h"
#include "core/segdicom/SegmentationDicom.h"
#include "core/segmentation/Labelmap.h"
#include "core/segmentation/SegmentEffects.h"
#include "core/segmentation/SegmentStatistics.h"
#include "core/segmentation/SegmentSurface.h"

namespace lucent::cli {
namespace {

std::string number(double v, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, v);
    return text;
}

// key=value, as --stats prints it (the volume as volume_ml).
std::string statsLine(const SegmentStatistics& s) {
    return "voxels=" + std::to_string(s.voxels) + " volume_ml=" + number(s.volumeMl, 4) +
           " mean=" + number(s.mean, 3) + " sd=" + number(s.standardDeviation, 3) +
           " min=" + number(s.minimum, 3) + " max=" + number(s.maximum, 3) +
           " median=" + number(s.median, 3) + " area_cm2=" + number(s.surfaceAreaCm2, 3) +
           " diameter_mm=" + number(s.largestDiameterMm, 2);
}

std::pair<double, double> rangeFlag(const QCommandLineParser& p) {
    const QStringList parts = p.value("threshold").split(',');
    bool ok1 = false, ok2 = false;
    const double lo = parts.size() == 2 ? parts[0].toDouble(&ok1) : 0.0;
    const double hi = parts.size() == 2 ? parts[1].toDouble(&ok2) : 0.0;
    if (!ok1 || !ok2 || lo > hi) {
        throw UsageError("--threshold: '" + p.value("threshold").toStdString() +
                         "' is not LO,HI with LO <= HI");
    }
    return {lo, hi};
}

bool niftiName(const QString& out) {
    return out.endsWith(".nii") || out.endsWith(".nii.gz");
}

bool segName(const QString& out) {
    return out.endsWith(".dcm", Qt::CaseInsensitive);
}

// A DICOM series of PATH (by id or UID, else the largest volume), loaded, with the headers of
// its images (what a SEG refers to).
struct DicomSeries {
    Volume volume;
    ReferencedSeries images;
};

DicomSeries loadDicomSeries(const std::string& path, const std::string& idOrUid) {
    const Catalog catalog = scanPath(path);
    const SeriesEntry* entry = idOrUid.empty() ? catalog.defaultEntry() : catalog.find(idOrUid);
    if (entry == nullptr) {
        throw std::runtime_error(path + ": no series " +
                                 (idOrUid.empty() ? std::string("to load") : idOrUid));
    }
    if (entry->format != SourceFormat::Dicom) {
        throw std::runtime_error(path + ": a DICOM SEG needs the DICOM series it lies on");
    }
    std::vector<std::filesystem::path> files;
    for (const SliceRef& slice : entry->slices) {
        if (files.empty() || files.back() != slice.file) {
            files.emplace_back(slice.file);
        }
    }
    return {loadSeries(*entry), readReferencedSeries(files)};
}

// The mask the flags ask for: threshold, then islands, then margin.
SegmentMask maskOf(const QCommandLineParser& p, const Volume& volume) {
    const auto [lo, hi] = rangeFlag(p);
    SegmentMask mask = thresholdMask(volume, lo, hi);
    if (p.isSet("keep-largest")) {
        mask = keepLargestIsland(mask);
    } else if (p.isSet("min-island-mm3")) {
        mask = removeSmallIslands(mask, volume.geometry(), numberFlag(p, "min-island-mm3", 0.0));
    }
    if (const double mm = numberFlag(p, "margin", 0.0); mm != 0.0) {
        mask = marginMask(mask, volume.geometry(), mm);
    }
    return mask;
}

// Parses, prints --help, runs `body` and turns its exceptions into the exit status:
// UsageError 2, anything else 3, each with the message after "lucent-cli NAME: ".
int guarded(const char* name, QCommandLineParser& parser, const QStringList& args,
            const std::function<int(QTextStream& out, QTextStream& err)>& body) {
    QTextStream err(stderr);
    QTextStream out(stdout);
    try {
        if (!parser.parse(args)) {
            throw UsageError(parser.errorText().toStdString());
        }
        if (parser.isSet("help")) {
            out << parser.helpText();
            return kOk;
        }
        return body(out, err);
    } catch (const UsageError& e) {
        err << "lucent-cli " << name << ": " << e.what() << "\n";
        return kUsage;
    } catch (const std::exception& e) {
        err << "lucent-cli " << name << ": " << e.what() << "\n";
        return kBadInput;
    }
}

} // namespace

int runSegment(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(
        "A segment of one series by threshold, islands and margin, written as a NIfTI labelmap "
        "(label 1) or, for OUT.dcm, a DICOM SEG on the series' images.");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    parser.addOption({"series", "Series id or UID (default: the largest volume).", "UID"});
    parser.addOption({"threshold", "Voxels with LO <= value <= HI (HU for CT).", "LO,HI"});
    parser.addOption({"keep-largest", "Keep the largest island (6-connected)."});
    parser.addOption({"min-island-mm3", "Remove islands smaller than N mm^3.", "N"});
    parser.addOption({"margin", "Grow (> 0) or shrink (< 0) by MM, exact Euclidean.", "MM"});
    parser.addOption({"name", "The segment's name.", "NAME", "Segment"});
    parser.addOption({{"o", "output"}, "The labelmap (.nii, .nii.gz) or DICOM SEG (.dcm).", "OUT"});
    parser.addOption({"stats", "Print the statistics as key=value."});
    parser.addOption({"surface",
                      "Also write the segment's surface (closed, smoothed) for "
                      "printing: .stl, .ply or .obj.",
                      "MESH"});
    parser.addHelpOption();
    return guarded("segment", parser, args, [&](QTextStream& out, QTextStream& err) {
        const QStringList positional = parser.positionalArguments();
        if (positional.size() != 1 || !parser.isSet("threshold") || !parser.isSet("output")) {
            throw UsageError("expected PATH, --threshold LO,HI and -o OUT.nii[.gz]|OUT.dcm");
        }
        const bool seg = segName(parser.value("output"));
        if (!niftiName(parser.value("output")) && !seg) {
            throw UsageError("-o: '" + parser.value("output").toStdString() +
                             "' must end in .nii, .nii.gz or .dcm");
        }
        if (parser.isSet("keep-largest") && parser.isSet("min-island-mm3")) {
            throw UsageError("--keep-largest and --min-island-mm3 exclude each other");
        }
        const std::filesystem::path surfaceFile = parser.value("surface").toStdString();
        if (parser.isSet("surface")) {
            try {
                meshFormatOf(surfaceFile);
            } catch (const std::invalid_argument& e) {
                throw UsageError(std::string("--surface: ") + e.what());
            }
        }
        DicomSeries series;
        if (seg) {
            series =
                loadDicomSeries(positional[0].toStdString(), parser.value("series").toStdString());
        } else {
            series.volume =
                loadPath(positional[0].toStdString(), parser.value("series").toStdString());
        }
        const Volume& volume = series.volume;
        SegmentMask mask = maskOf(parser, volume);
        if (!mask.any()) {
            err << "lucent-cli segment: no voxel left in " << positional[0] << " (threshold "
                << parser.value("threshold") << "); nothing written\n";
            return kBadInput;
        }
        Segmentation segmentation(volume.geometry());
        const std::uint32_t id = segmentation.add(parser.value("name").toStdString());
        segmentation.setMask(id, std::move(mask), "Threshold", "Lucent threshold");
        if (seg) {
            writeSegmentationDicom(parser.value("output").toStdString(), segmentation,
                                   series.images);
        } else {
            writeNifti(parser.value("output").toStdString(), labelmapOf(segmentation));
        }
        if (parser.isSet("surface")) {
            const Segment& segment = *segmentation.find(id);
            const SurfaceResult surface =
                segmentSurface(*segment.mask, volume.geometry(), {}, segment.name);
            MeshFileContent content;
            content.description = "Lucent segment " + segment.name;
            writeMesh(surface.mesh, surfaceFile, meshFormatOf(surfaceFile), content);
        }
        if (parser.isSet("stats")) {
            out << QString::fromStdString(
                       statsLine(segmentStatistics(*segmentation.find(id)->mask, volume)))
                << "\n";
        }
        return kOk;
    });
}

int runSegmentStats(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(
        "The statistics of each label of a NIfTI labelmap, or each segment of a DICOM SEG, on a "
        "series: one key=value line per label (a SEG's segments with their number, codes and "
        "algorithm).");
    parser.addPositionalArgument("PATH", "the series the labels lie on");
    parser.addPositionalArgument("LABELS", "a NIfTI labelmap (.nii, .nii.gz) on its grid, or a "
                                           "DICOM SEG that refers to the series");
    parser.addOption({"series", "Series id or UID (default: the largest volume).", "UID"});
    parser.addHelpOption();
    return guarded("segment-stats", parser, args, [&](QTextStream& out, QTextStream& err) {
        const QStringList positional = parser.positionalArguments();
        if (positional.size() != 2) {
            throw UsageError("expected PATH and LABELS");
        }
        const std::string labelsFile = positional[1].toStdString();
        if (!niftiName(positional[1])) {
            const DicomSeries series =
                loadDicomSeries(positional[0].toStdString(), parser.value("series").toStdString());
            const ReadSegmentationDicom read =
                readSegmentationDicom(labelsFile, series.images, series.volume.geometry());
            for (const std::string& note : read.notes) {
                err << "lucent-cli segment-stats: " << positional[1] << ": "
                    << QString::fromStdString(note) << "\n";
            }
            for (std::size_t i = 0; i < read.segments.size(); ++i) {
                const Segment& s = read.segments[i];
                out << "number=" << read.segmentNumbers[i] << " label=\""
                    << QString::fromStdString(s.name) << "\" category=\""
                    << QString::fromStdString(s.category.meaning) << "\" type=\""
                    << QString::fromStdString(s.type.meaning)
                    << "\" type_code=" << QString::fromStdString(s.type.scheme + ":" + s.type.value)
                    << " algorithm=" << QString::fromStdString(s.algorithmType)
                    << (read.readOnly ? " read_only=1 " : " ")
                    << QString::fromStdString(statsLine(segmentStatistics(*s.mask, series.volume)))
                    << "\n";
            }
            return kOk;
        }
        const Volume volume =
            loadPath(positional[0].toStdString(), parser.value("series").toStdString());
        const Volume labels = readNifti(labelsFile);
        Segmentation segmentation(volume.geometry());
        try {
            importLabelmap(segmentation, labels);
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(labelsFile + ": " + e.what());
        }
        for (const Segment& s : segmentation.segments()) {
            out << "label=\"" << QString::fromStdString(s.name) << "\" "
                << QString::fromStdString(statsLine(segmentStatistics(*s.mask, volume))) << "\n";
        }
        return kOk;
    });
}

} // namespace lucent::cli
