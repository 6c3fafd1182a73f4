// Exports of real DICOM (CT, a segmentation referencing it, JPEG lossless):
// de-identified to a folder with a DICOMDIR and to a ZIP, every element of
// every exported file searched for the originals' identifying values, pixels
// compared byte for byte, failures leaving nothing behind.
#include <QCryptographicHash>
#include <QFile>
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>
#include <set>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcmetinf.h>
#include <dcmtk/dcmdata/dcpixel.h>
#include <dcmtk/dcmdata/dcpixseq.h>
#include <dcmtk/dcmdata/dcpxitem.h>
#include <dcmtk/dcmdata/dcuid.h>

#include "core/exchange/DicomExport.h"
#include "core/io/Catalog.h"
#include "tests/support/CliRunner.h"
#include "tests/support/RealData.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

const fs::path kData = test::kRealData;

// Text attributes that identify a person, place or study besides every PN,
// DA, DT and non-standard UI value.
const DcmTagKey kIdentifyingText[] = {DCM_PatientID,
                                      DCM_RETIRED_OtherPatientIDs,
                                      DCM_AccessionNumber,
                                      DCM_InstitutionName,
                                      DCM_InstitutionAddress,
                                      DCM_StationName,
                                      DCM_StudyID,
                                      DCM_DeviceSerialNumber,
                                      DCM_PatientAddress,
                                      DCM_StudyDescription,
                                      DCM_SeriesDescription,
                                      DCM_ProtocolName,
                                      DCM_InstitutionalDepartmentName,
                                      DCM_RequestedProcedureDescription};

// Visits every element of an item and its sequences' items, depth first.
template <class Visit> void eachElement(DcmItem& item, Visit visit) {
    for (unsigned long k = 0; k < item.card(); ++k) {
        DcmElement* e = item.getElement(k);
        visit(*e);
        if (e->ident() == EVR_SQ) {
            auto& sq = static_cast<DcmSequenceOfItems&>(*e);
            for (unsigned long n = 0; n < sq.card(); ++n) {
                eachElement(*sq.getItem(n), visit);
            }
        }
    }
}

std::string textOf(DcmElement& e) {
    OFString v;
    return e.isaString() && e.getOFStringArray(v).good() ? std::string(v.c_str()) : std::string();
}

std::set<std::string> identifyingValues(const std::vector<fs::path>& files) {
    std::set<std::string> out;
    for (const fs::path& f : files) {
        DcmFileFormat ff;
        if (ff.loadFile(f.c_str()).bad()) {
            continue;
        }
        eachElement(*ff.getDataset(), [&](DcmElement& e) {
            const std::string v = textOf(e);
            const DcmEVR vr = e.ident();
            const bool named = std::any_of(std::begin(kIdentifyingText), std::end(kIdentifyingText),
                                           [&](const DcmTagKey& t) { return e.getTag() == t; });
            const bool uid = vr == EVR_UI && dcmFindNameOfUID(v.c_str()) == nullptr;
            if (v.size() >= 4 && (vr == EVR_PN || vr == EVR_DA || vr == EVR_DT || uid || named)) {
                out.insert(v);
            }
        });
    }
    return out;
}

// The pixel data's bytes: native, or every fragment of an encapsulated one.
QByteArray pixelBytes(const fs::path& file) {
    DcmFileFormat ff;
    if (ff.loadFile(file.c_str()).bad()) {
        return {};
    }
    DcmElement* e = nullptr;
    if (ff.getDataset()->findAndGetElement(DCM_PixelData, e).bad()) {
        return {};
    }
    auto& px = static_cast<DcmPixelData&>(*e);
    DcmPixelSequence* seq = nullptr;
    const E_TransferSyntax xfer = ff.getDataset()->getOriginalXfer();
    QByteArray out;
    if (DcmXfer(xfer).isEncapsulated() &&
        px.getEncapsulatedRepresentation(xfer, nullptr, seq).good() && seq) {
        for (unsigned long n = 0; n < seq->card(); ++n) {
            DcmPixelItem* item = nullptr;
            Uint8* bytes = nullptr;
            if (seq->getItem(item, n).good() && item->getUint8Array(bytes).good() && bytes) {
                out.append(reinterpret_cast<const char*>(bytes), qsizetype(item->getLength()));
            }
        }
        return out;
    }
    Uint8* bytes = nullptr;
    if (px.getUint8Array(bytes).good() && bytes) {
        out = QByteArray(reinterpret_cast<const char*>(bytes), qsizetype(px.getLength()));
    }
    return out;
}

QByteArray fileBytes(const fs::path& f) {
    QFile file(QString::fromStdString(f.string()));
    return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray();
}

// A DICOMDIR's records, without its meta header (which names a new file-set
// instance each time one is written).
QByteArray directoryRecords(const fs::path& dicomdir, const fs::path& scratch) {
    DcmFileFormat ff;
    if (ff.loadFile(dicomdir.c_str()).bad() ||
        ff.getDataset()->saveFile(scratch.c_str(), EXS_LittleEndianExplicit).bad()) {
        return {};
    }
    return fileBytes(scratch);
}

std::vector<fs::path> filesUnder(const fs::path& root) {
    std::vector<fs::path> out;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
        if (e.is_regular_file()) {
            out.push_back(e.path());
        }
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<fs::path> sources() {
    return {kData / "dcmqi_ct3slice/01.dcm", kData / "dcmqi_ct3slice/02.dcm",
            kData / "dcmqi_ct3slice/03.dcm", kData / "dcmqi_ct3slice/liver_seg.dcm",
            kData / "nema_wg04/CT1/CT1_JPLL.dcm"};
}

std::vector<InstanceHeader> headersOf(const std::vector<fs::path>& files) {
    std::vector<InstanceHeader> out;
    for (const fs::path& f : files) {
        out.push_back(readInstanceHeader(f));
    }
    return out;
}

bool leftovers(const fs::path& folder) {
    for (const auto& e : fs::directory_iterator(folder)) {
        if (e.path().filename().string().find(".partial-") != std::string::npos) {
            return true;
        }
    }
    return false;
}

} // namespace

class TestDicomExport : public QObject {
    Q_OBJECT
private slots:
    void anonymizedExportKeepsNoIdentifierAndEveryPixel();
    void segmentationStillReferencesItsExportedSeries();
    void dicomdirOpensInLucentAndDcmdump();
    void zipUnzipsToTheFolderExport();
    void failureLeavesNothing();
    void neverWritesIntoTheSource();
    void commandLine();
};

void TestDicomExport::anonymizedExportKeepsNoIdentifierAndEveryPixel() {
    REQUIRE_DATA("dcmqi_ct3slice");
    REQUIRE_DATA("nema_wg04/CT1");
    QTemporaryDir out;
    const fs::path target = fs::path(out.path().toStdString()) / "anonymous";
    ExportOptions options;
    options.anonymize = true;
    options.dicomdir = true;
    const ExportResult r = exportInstances(headersOf(sources()), target, options);
    QCOMPARE(r.files, 5);
    const std::set<std::string> identifying = identifyingValues(sources());
    QVERIFY(identifying.size() > 20); // names, dates, UIDs: the check has something to find
    int elements = 0;
    for (const fs::path& f : filesUnder(target)) {
        DcmFileFormat ff;
        QVERIFY2(ff.loadFile(f.c_str()).good(), f.c_str());
        const auto check = [&](DcmElement& e) {
            ++elements;
            const std::string v = textOf(e);
            for (const std::string& original : identifying) {
                if (v.find(original) != std::string::npos) {
                    QFAIL(qPrintable(
                        QString("%1: %2 still holds '%3'")
                            .arg(f.c_str(), e.getTag().toString().c_str(), original.c_str())));
                }
            }
        };
        eachElement(*ff.getMetaInfo(), check);
        eachElement(*ff.getDataset(), check);
    }
    QVERIFY(elements > 500);
    for (std::size_t k = 0; k < sources().size(); ++k) {
        const QByteArray original = pixelBytes(sources()[k]);
        QVERIFY(original.size() > 10000);
        QVERIFY2(pixelBytes(target / r.fileIds[k]) == original, r.fileIds[k].c_str());
        DcmFileFormat ff;
        ff.loadFile((target / r.fileIds[k]).c_str());
        OFString removed, patientId;
        ff.getDataset()->findAndGetOFString(DCM_PatientIdentityRemoved, removed);
        QCOMPARE(std::string(removed.c_str()), std::string("YES"));
        ff.getDataset()->findAndGetOFString(DCM_PatientID, patientId);
        QVERIFY(QString(patientId.c_str()).startsWith("ANON"));
    }
}

void TestDicomExport::segmentationStillReferencesItsExportedSeries() {
    REQUIRE_DATA("dcmqi_ct3slice");
    QTemporaryDir out;
    const fs::path target = fs::path(out.path().toStdString()) / "anonymous";
    ExportOptions options;
    options.anonymize = true;
    const std::vector<fs::path> all = sources();
    const std::vector<fs::path> files(all.begin(), all.begin() + 4);
    const ExportResult r = exportInstances(headersOf(files), target, options);
    std::set<std::string> ctInstances;
    std::string ctSeries;
    for (int k = 0; k < 3; ++k) {
        const InstanceHeader h = readInstanceHeader(target / r.fileIds[k]);
        ctInstances.insert(h.sopInstanceUid);
        ctSeries = h.seriesUid;
        QVERIFY(h.sopInstanceUid != readInstanceHeader(files[k]).sopInstanceUid);
    }
    DcmFileFormat seg;
    QVERIFY(seg.loadFile((target / r.fileIds[3]).c_str()).good());
    DcmItem* series = nullptr;
    QVERIFY(seg.getDataset()->findAndGetSequenceItem(DCM_ReferencedSeriesSequence, series).good());
    OFString referencedSeries;
    series->findAndGetOFString(DCM_SeriesInstanceUID, referencedSeries);
    QCOMPARE(std::string(referencedSeries.c_str()), ctSeries);
    int referenced = 0;
    DcmItem* instance = nullptr;
    while (series->findAndGetSequenceItem(DCM_ReferencedInstanceSequence, instance, referenced)
               .good()) {
        OFString uid;
        instance->findAndGetOFString(DCM_ReferencedSOPInstanceUID, uid);
        QVERIFY2(ctInstances.count(uid.c_str()) == 1, uid.c_str());
        ++referenced;
    }
    QCOMPARE(referenced, 3);
}

void TestDicomExport::dicomdirOpensInLucentAndDcmdump() {
    REQUIRE_DATA("dcmqi_ct3slice");
    QTemporaryDir out;
    const fs::path target = fs::path(out.path().toStdString()) / "media";
    ExportOptions options;
    options.anonymize = true;
    options.dicomdir = true;
    exportInstances(headersOf(sources()), target, options);
    const Catalog c = scanPath(target / "DICOMDIR");
    const auto ct = std::find_if(c.series.begin(), c.series.end(),
                                 [](const SeriesEntry& e) { return e.kind == SeriesKind::Volume; });
    QVERIFY(ct != c.series.end());
    QCOMPARE(ct->geometry.dims.z, 3);
    QProcess dump;
    dump.start("dcmdump", {QString::fromStdString((target / "DICOMDIR").string())});
    QVERIFY2(dump.waitForStarted(), "dcmdump (Debian's dcmtk) is needed and was not found");
    QVERIFY(dump.waitForFinished(60000));
    QCOMPARE(dump.exitCode(), 0);
    const QString listing = QString::fromUtf8(dump.readAllStandardOutput());
    QCOMPARE(listing.count("ReferencedFileID"), 5);
    QCOMPARE(listing.count("[PATIENT]"), 2); // one pseudonym per original patient
}

void TestDicomExport::zipUnzipsToTheFolderExport() {
    REQUIRE_DATA("dcmqi_ct3slice");
    QTemporaryDir out;
    const fs::path root = out.path().toStdString();
    ExportOptions options;
    options.dicomdir = true;
    const ExportResult folder = exportInstances(headersOf(sources()), root / "folder", options);
    const ExportResult zip = exportInstances(headersOf(sources()), root / "media.zip", options);
    QVERIFY(zip.zip && fs::is_regular_file(root / "media.zip"));
    QProcess unzip;
    unzip.start("python3",
                {"-m", "zipfile", "-e", QString::fromStdString((root / "media.zip").string()),
                 QString::fromStdString((root / "unzipped").string())});
    QVERIFY2(unzip.waitForStarted(), "python3 is needed to unzip and was not found");
    QVERIFY(unzip.waitForFinished(60000));
    QCOMPARE(unzip.exitCode(), 0);
    const std::vector<fs::path> a = filesUnder(root / "folder");
    const std::vector<fs::path> b = filesUnder(root / "unzipped");
    QCOMPARE(a.size(), std::size_t(6)); // 5 instances and the DICOMDIR
    QCOMPARE(b.size(), a.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
        QCOMPARE(a[k].lexically_relative(root / "folder"),
                 b[k].lexically_relative(root / "unzipped"));
        if (a[k].filename() == "DICOMDIR") {
            const QByteArray records = directoryRecords(a[k], root / "a.records");
            QVERIFY(records.size() > 1000);
            QVERIFY(records == directoryRecords(b[k], root / "b.records"));
        } else {
            QVERIFY2(fileBytes(a[k]) == fileBytes(b[k]), a[k].c_str());
        }
    }
    for (std::size_t k = 0; k < sources().size(); ++k) { // not de-identified: the files as they are
        QVERIFY(fileBytes(root / "folder" / folder.fileIds[k]) == fileBytes(sources()[k]));
    }
}

void TestDicomExport::failureLeavesNothing() {
    REQUIRE_DATA("dcmqi_ct3slice");
    QTemporaryDir source, out;
    const fs::path src = source.path().toStdString();
    fs::copy_file(kData / "dcmqi_ct3slice/01.dcm", src / "a.dcm");
    fs::copy_file(kData / "dcmqi_ct3slice/02.dcm", src / "b.dcm");
    DcmFileFormat ff; // the third has text burned into its pixels: the profile cannot clean it
    QVERIFY(ff.loadFile((kData / "dcmqi_ct3slice/03.dcm").c_str()).good());
    ff.getDataset()->putAndInsertString(DCM_BurnedInAnnotation, "YES");
    QVERIFY(ff.saveFile((src / "c.dcm").c_str()).good());
    std::vector<std::string> passedOver;
    const std::vector<InstanceHeader> instances = collectInstances(src, "", passedOver);
    QCOMPARE(instances.size(), std::size_t(3));
    const fs::path root = out.path().toStdString();
    for (const char* name : {"anonymous", "anonymous.zip"}) {
        ExportOptions options;
        options.anonymize = true;
        try {
            exportInstances(instances, root / name, options);
            QFAIL("a file with burned-in annotation was exported de-identified");
        } catch (const ExportError& e) {
            QVERIFY2(QString(e.what()).contains("c.dcm") && QString(e.what()).contains("burned-in"),
                     e.what());
        }
        QVERIFY(!fs::exists(root / name));
        QVERIFY(!leftovers(root));
    }
    // Cancelled after the first file: nothing either.
    std::stop_source stop;
    ExportOptions options;
    options.stop = stop.get_token();
    options.onProgress = [&](int, int) { stop.request_stop(); };
    QVERIFY_THROWS_EXCEPTION(ExportError, exportInstances(instances, root / "cancelled", options));
    QVERIFY(!fs::exists(root / "cancelled"));
    QVERIFY(!leftovers(root));
}

void TestDicomExport::neverWritesIntoTheSource() {
    REQUIRE_DATA("dcmqi_ct3slice");
    QTemporaryDir source;
    const fs::path src = source.path().toStdString();
    fs::create_directory(src / "series");
    for (const char* f : {"01.dcm", "02.dcm"}) {
        fs::copy_file(kData / "dcmqi_ct3slice" / f, src / "series" / f);
    }
    std::vector<std::string> passedOver;
    const std::vector<InstanceHeader> instances = collectInstances(src, "", passedOver);
    const QByteArray before = fileBytes(src / "series/01.dcm") + fileBytes(src / "series/02.dcm");
    ExportOptions options;
    options.anonymize = true;
    try {
        exportInstances(instances, src / "series" / "out", options);
        QFAIL("exported into the source folder");
    } catch (const ExportError& e) {
        QVERIFY2(QString(e.what()).contains("inside the source folder"), e.what());
    }
    exportInstances(instances, src / "out", options); // beside the series: allowed
    try {
        exportInstances(instances, src / "out", options);
        QFAIL("overwrote an export");
    } catch (const ExportError& e) {
        QVERIFY2(QString(e.what()).contains("exists already"), e.what());
    }
    QCOMPARE(fileBytes(src / "series/01.dcm") + fileBytes(src / "series/02.dcm"), before);
    QCOMPARE(filesUnder(src / "series").size(), std::size_t(2));
}

void TestDicomExport::commandLine() {
    REQUIRE_DATA("dcmqi_ct3slice");
    QTemporaryDir out;
    const QString data = QString::fromStdString((kData / "dcmqi_ct3slice").string());
    const QString zip = out.filePath("study.zip");
    test::CliRun run = test::runCli({"export", data, "-o", zip, "--anonymize", "--dicomdir"});
    QVERIFY2(run.exitCode == 0, qPrintable(run.err));
    QVERIFY2(run.out.contains("4 instance(s) exported, de-identified,"), qPrintable(run.out));
    QVERIFY(QFile::exists(zip));
    const std::string ct = readInstanceHeader(kData / "dcmqi_ct3slice/01.dcm").seriesUid;
    run = test::runCli(
        {"export", data, "-o", out.filePath("ct"), "--series", QString::fromStdString(ct)});
    QVERIFY2(run.exitCode == 0, qPrintable(run.err));
    QVERIFY2(run.out.startsWith("3 instance(s) exported"), qPrintable(run.out));
    run = test::runCli({"export", data, "-o", zip});
    QCOMPARE(run.exitCode, 3);
    QVERIFY2(run.err.contains("exists already"), qPrintable(run.err));
    run = test::runCli({"export", data});
    QCOMPARE(run.exitCode, 2);
}

QTEST_GUILESS_MAIN(TestDicomExport)
#include "test_dicom_export.moc"
