#pragma once
// A SEG of Lucent's segments written by dcmjs (OHIF's DICOM library) through node and
// tests/segdicom/dcmjs/write-seg.js: the foreign writer of the SEG tests and benchmark.
// packaging/install-deps.sh installs node and dcmjs (npm ci in tests/segdicom/dcmjs).

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmiod/cielabutil.h>

#include "core/report/ReferencedSeries.h"
#include "core/segmentation/Segmentation.h"

namespace lucent::test {

struct DcmjsRun {
    bool ok = false;
    std::string message; // why it did not run
    std::filesystem::path file;
    double parseMs = 0.0; // node reading the CT
    double writeMs = 0.0; // dcmjs normalizing, deriving, filling and encoding the SEG
};

inline QJsonObject codeJson(const CodedConcept& c) {
    return {{"value", QString::fromStdString(c.value)},
            {"scheme", QString::fromStdString(c.scheme)},
            {"meaning", QString::fromStdString(c.meaning)}};
}

// Writes the segments of `seg` on `series` with dcmjs into dir/dcmjs.seg.dcm (FRACTIONAL with
// RLE, OHIF's default, when rle).
inline DcmjsRun writeWithDcmjs(const Segmentation& seg, const ReferencedSeries& series,
                               const std::filesystem::path& dir, bool rle = false) {
    namespace fs = std::filesystem;
    DcmjsRun run;
    const fs::path script = fs::path(LUCENT_SOURCE_DIR) / "tests/segdicom/dcmjs/write-seg.js";
    if (!fs::exists(script.parent_path() / "node_modules/dcmjs")) {
        run.message = "dcmjs is not installed: packaging/install-deps.sh (npm ci in " +
                      script.parent_path().string() + ")";
        return run;
    }
    const VolumeGeometry& grid = seg.geometry();
    QJsonArray ctFiles;
    QJsonArray sliceUids;
    std::vector<std::string> uids(static_cast<std::size_t>(grid.dims.z));
    for (const ReferencedImage& image : series.images) {
        ctFiles.append(QString::fromStdString(image.file.string()));
        const long k = std::lround(grid.toIndex(image.position).z);
        if (k >= 0 && k < grid.dims.z) {
            uids[static_cast<std::size_t>(k)] = image.sopInstanceUid;
        }
    }
    for (const std::string& uid : uids) {
        sliceUids.append(QString::fromStdString(uid));
    }
    QJsonArray segments;
    for (std::size_t s = 0; s < seg.segments().size(); ++s) {
        const Segment& segment = seg.segments()[s];
        const fs::path maskFile = dir / ("mask" + std::to_string(s) + ".bits");
        std::ofstream out(maskFile, std::ios::binary);
        const auto words = segment.mask->words(); // bit n is voxel n: little-endian bytes
        out.write(reinterpret_cast<const char*>(words.data()),
                  static_cast<std::streamsize>(words.size() * sizeof(std::uint64_t)));
        double l = 0, a = 0, b = 0;
        IODCIELabUtil::rgb2DicomLab(l, a, b, segment.colour[0] / 255.0, segment.colour[1] / 255.0,
                                    segment.colour[2] / 255.0);
        segments.append(QJsonObject{
            {"label", QString::fromStdString(segment.name)},
            {"category", codeJson(segment.category)},
            {"type", codeJson(segment.type)},
            {"algorithmType", QString::fromStdString(segment.algorithmType)},
            {"algorithmName", QString::fromStdString(segment.algorithmName)},
            {"lab", QJsonArray{static_cast<int>(std::lround(l)), static_cast<int>(std::lround(a)),
                               static_cast<int>(std::lround(b))}},
            {"maskFile", QString::fromStdString(maskFile.string())}});
    }
    run.file = dir / "dcmjs.seg.dcm";
    const QJsonObject job{{"ctFiles", ctFiles},
                          {"sliceUids", sliceUids},
                          {"rows", grid.dims.y},
                          {"columns", grid.dims.x},
                          {"segments", segments},
                          {"rle", rle},
                          {"output", QString::fromStdString(run.file.string())}};
    const fs::path jobFile = dir / "dcmjs-job.json";
    std::ofstream(jobFile) << QJsonDocument(job).toJson().toStdString();
    QProcess node;
    node.start("node",
               {QString::fromStdString(script.string()), QString::fromStdString(jobFile.string())});
    if (!node.waitForStarted(10000)) {
        run.message = "node did not start: packaging/install-deps.sh installs nodejs";
        return run;
    }
    node.waitForFinished(600000);
    const QJsonObject result = QJsonDocument::fromJson(node.readAllStandardOutput()).object();
    if (node.exitCode() != 0 || !result.contains("writeMs")) {
        run.message = "write-seg.js failed: " + node.readAllStandardError().toStdString();
        return run;
    }
    run.ok = true;
    run.parseMs = result.value("parseMs").toDouble();
    run.writeMs = result.value("writeMs").toDouble();
    return run;
}

} // namespace lucent::test
