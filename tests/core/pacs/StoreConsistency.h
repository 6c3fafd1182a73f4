#pragma once
// For the fault tests of retrievals: what a study store must look like after
// any failure. No temporary file is left, every file under files/ is indexed,
// every indexed instance has its file, and every file parses whole with DCMTK
// (pixel data of the size its rows, columns and bits say).

#include <QString>
#include <QTest>

#include <filesystem>
#include <set>
#include <string>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include "core/store/StudyStore.h"

namespace lucent::test {

// Empty when the file is a whole DICOM image, else what is wrong with it.
inline QString wholeDicomProblem(const std::filesystem::path& file) {
    DcmFileFormat dicom;
    if (const OFCondition c = dicom.loadFile(file.c_str()); c.bad()) {
        return QString::fromStdString(file.string()) + ": does not parse: " + c.text();
    }
    DcmDataset& d = *dicom.getDataset();
    Uint16 rows = 0;
    Uint16 columns = 0;
    Uint16 bits = 0;
    DcmElement* pixels = nullptr;
    if (d.findAndGetUint16(DCM_Rows, rows).bad() ||
        d.findAndGetUint16(DCM_Columns, columns).bad() ||
        d.findAndGetUint16(DCM_BitsAllocated, bits).bad() ||
        d.findAndGetElement(DCM_PixelData, pixels).bad() || pixels == nullptr) {
        return QString::fromStdString(file.string()) + ": no image (rows, columns, pixel data)";
    }
    const Uint32 want = Uint32(rows) * columns * (bits / 8);
    if (pixels->getLength() != want) {
        return QString::fromStdString(file.string()) +
               QString(": pixel data of %1 bytes, not %2").arg(pixels->getLength()).arg(want);
    }
    return {};
}

// Checks the store's files against its index (see above); the number of
// instances of `seriesUid` it holds, or -1 after a failed check.
inline int checkStoreConsistent(StudyStore& store, const std::string& seriesUid) {
    namespace fs = std::filesystem;
    const fs::path tmp = store.root() / "tmp";
    for (const auto& left : fs::directory_iterator(tmp)) {
        QTest::qFail(
            qPrintable("a temporary file is left: " + QString::fromStdString(left.path().string())),
            __FILE__, __LINE__);
        return -1;
    }
    std::size_t indexed = 0;
    for (const StoredSeries& s : store.listSeries()) {
        const std::set<std::string> instances = store.instancesOf(s.info.seriesUid);
        indexed += instances.size();
        std::set<std::string> onDisk;
        if (fs::is_directory(s.folder)) {
            for (const auto& f : fs::directory_iterator(s.folder)) {
                onDisk.insert(f.path().stem().string());
                if (const QString problem = wholeDicomProblem(f.path()); !problem.isEmpty()) {
                    QTest::qFail(qPrintable(problem), __FILE__, __LINE__);
                    return -1;
                }
            }
        }
        if (onDisk != instances) {
            QTest::qFail(qPrintable(QString("series %1: %2 file(s) on disk, %3 in the index")
                                        .arg(QString::fromStdString(s.info.seriesUid))
                                        .arg(onDisk.size())
                                        .arg(instances.size())),
                         __FILE__, __LINE__);
            return -1;
        }
    }
    std::size_t files = 0;
    for (const auto& f : fs::recursive_directory_iterator(store.root() / "files")) {
        files += f.is_regular_file() ? 1 : 0;
    }
    if (files != indexed) {
        QTest::qFail(
            qPrintable(QString("%1 file(s) under files/, %2 indexed").arg(files).arg(indexed)),
            __FILE__, __LINE__);
        return -1;
    }
    return int(store.instancesOf(seriesUid).size());
}

} // namespace lucent::test
