// The PS3.15 basic-profile de-identifier on real DICOM series: the copies
// (read back with DCMTK, independent of the GDCM writer) hold no patient name,
// ID or birth date, no institution, dates or private attributes, new UIDs
// that still tie the series together, and load as the same volume.
#include <QTest>

#include <dcmtk/dcmdata/dctk.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/dicom/Deidentifier.h"
#include "core/io/Catalog.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

fs::path dataPath(const char* relative) {
    return fs::path(LUCENT_TEST_DATA_DIR) / relative;
}

std::vector<fs::path> filesOf(const fs::path& folder) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder)) {
        if (entry.is_regular_file()) {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

struct Dataset {
    DcmFileFormat file;
    bool ok = false;
    explicit Dataset(const fs::path& path) { ok = file.loadFile(path.c_str()).good(); }
    OFString text(const DcmTagKey& key) {
        OFString value;
        file.getDataset()->findAndGetOFStringArray(key, value);
        return value;
    }
    bool has(const DcmTagKey& key) { return file.getDataset()->tagExists(key); }
    bool hasPrivate() {
        DcmDataset* ds = file.getDataset();
        for (unsigned long n = 0; n < ds->card(); ++n) {
            if (ds->getElement(n)->getTag().isPrivate()) {
                return true;
            }
        }
        return false;
    }
};

} // namespace

class TestDeidentifier : public QObject {
    Q_OBJECT

private slots:
    void seriesLosesIdentityKeepsVolume_data() {
        QTest::addColumn<QString>("series");
        QTest::newRow("philips phantom 5 mm") << "dcm_qa_ct/Philips_S21570/S2010";
        QTest::newRow("ge head, tilt and gaps") << "dcm_qa_ct/GE_head_tilt_varspacing";
    }
    void seriesLosesIdentityKeepsVolume() {
        QFETCH(QString, series);
        const fs::path source = dataPath(series.toUtf8().constData());
        if (!fs::is_directory(source)) {
            QSKIP("the real DICOM data (../shared/data) is absent");
        }
        const std::vector<fs::path> files = filesOf(source);
        QVERIFY(files.size() > 2);
        QTemporaryDir dir;
        const fs::path destination = fs::path(dir.path().toStdString()) / "copy";
        const std::vector<fs::path> copies = deidentifySeries(files, destination);
        QCOMPARE(copies.size(), files.size());
        QCOMPARE(filesOf(destination).size(), files.size());
        QCOMPARE(filesOf(destination.parent_path()).size(), std::size_t(0)); // no staging left

        std::set<std::string> seriesUids, studyUids, instanceUids;
        for (std::size_t n = 0; n < files.size(); ++n) {
            Dataset original(files[n]);
            Dataset copy(copies[n]);
            QVERIFY(original.ok && copy.ok);
            // Identifying attributes are blank or gone.
            for (const DcmTagKey& key :
                 {DCM_PatientName, DCM_PatientID, DCM_PatientBirthDate, DCM_PatientSex,
                  DCM_StudyDate, DCM_StudyTime, DCM_AccessionNumber, DCM_ReferringPhysicianName,
                  DCM_StudyID}) {
                QVERIFY2(copy.text(key).empty(), key.toString().c_str());
            }
            for (const DcmTagKey& key :
                 {DCM_InstitutionName, DCM_InstitutionAddress, DCM_StationName,
                  DCM_SeriesDescription, DCM_StudyDescription, DCM_OperatorsName, DCM_PatientAge,
                  DCM_PatientWeight, DCM_SeriesDate, DCM_AcquisitionDate, DCM_DeviceSerialNumber,
                  DCM_OtherPatientNames, DCM_PatientAddress}) {
                QVERIFY2(!copy.has(key), key.toString().c_str());
            }
            QVERIFY(!copy.hasPrivate());
            QCOMPARE(copy.text(DCM_PatientIdentityRemoved), OFString("YES"));
            // New UIDs, consistent within the series.
            for (const DcmTagKey& key :
                 {DCM_SeriesInstanceUID, DCM_StudyInstanceUID, DCM_SOPInstanceUID}) {
                QVERIFY(!copy.text(key).empty());
                QVERIFY(copy.text(key) != original.text(key));
            }
            if (original.has(DCM_FrameOfReferenceUID)) {
                QVERIFY(copy.text(DCM_FrameOfReferenceUID) !=
                        original.text(DCM_FrameOfReferenceUID));
            }
            QCOMPARE(copy.text(DCM_SOPClassUID), original.text(DCM_SOPClassUID));
            OFString mediaInstance;
            copy.file.getMetaInfo()->findAndGetOFString(DCM_MediaStorageSOPInstanceUID,
                                                        mediaInstance);
            QCOMPARE(mediaInstance, copy.text(DCM_SOPInstanceUID));
            seriesUids.insert(copy.text(DCM_SeriesInstanceUID).c_str());
            studyUids.insert(copy.text(DCM_StudyInstanceUID).c_str());
            instanceUids.insert(copy.text(DCM_SOPInstanceUID).c_str());
            // Pixels and geometry untouched.
            QCOMPARE(copy.text(DCM_ImagePositionPatient), original.text(DCM_ImagePositionPatient));
            QCOMPARE(copy.text(DCM_ImageOrientationPatient),
                     original.text(DCM_ImageOrientationPatient));
        }
        QCOMPARE(seriesUids.size(), std::size_t(1));
        QCOMPARE(studyUids.size(), std::size_t(1));
        QCOMPARE(instanceUids.size(), files.size());

        // The same volume: geometry and every voxel.
        const Volume before = loadPath(source);
        const Volume after = loadPath(destination);
        QVERIFY(before.geometry().dims == after.geometry().dims);
        QVERIFY(before.geometry().spacing == after.geometry().spacing);
        QVERIFY(before.geometry().origin == after.geometry().origin);
        QVERIFY(before.geometry().direction == after.geometry().direction);
        QCOMPARE(before.bytes().size(), after.bytes().size());
        QVERIFY(std::memcmp(before.bytes().data(), after.bytes().data(), before.bytes().size()) ==
                0);
        // The catalog's patient fields are empty too.
        const Catalog catalog = scanPath(destination);
        QCOMPARE(catalog.series.size(), std::size_t(1));
        QVERIFY(catalog.series[0].patientName.empty());
        QVERIFY(catalog.series[0].patientId.empty());
        QVERIFY(catalog.series[0].description.empty());
    }

    void refusesBadInputWithoutLeavingHalfACopy() {
        QTemporaryDir dir;
        const fs::path root = dir.path().toStdString();
        const fs::path bogus = root / "not-dicom.dcm";
        { std::ofstream(bogus) << "hello"; }
        try {
            deidentifySeries({bogus}, root / "copy");
            QFAIL("no error");
        } catch (const DeidentifyError& e) {
            QVERIFY2(std::string(e.what()).find("not-dicom.dcm") != std::string::npos, e.what());
        }
        QVERIFY(!fs::exists(root / "copy"));
        QCOMPARE(filesOf(root).size(), std::size_t(1)); // only the bogus file
        for (const auto& entry : fs::directory_iterator(root)) {
            QVERIFY(entry.is_regular_file()); // no staging folder left
        }
        fs::create_directory(root / "taken");
        QVERIFY_THROWS_EXCEPTION(DeidentifyError, deidentifySeries({bogus}, root / "taken"));
    }

    void refusesBurnedInAnnotation() {
        const fs::path source = dataPath("dcm_qa_ct/Philips_S21570/S2010");
        if (!fs::is_directory(source)) {
            QSKIP("the real DICOM data (../shared/data) is absent");
        }
        QTemporaryDir dir;
        const fs::path root = dir.path().toStdString();
        const fs::path marked = root / "burned.dcm";
        DcmFileFormat file;
        QVERIFY(file.loadFile(filesOf(source).front().c_str()).good());
        QVERIFY(file.getDataset()->putAndInsertString(DCM_BurnedInAnnotation, "YES").good());
        QVERIFY(file.saveFile(marked.c_str()).good());
        try {
            deidentifySeries({marked}, root / "copy");
            QFAIL("no error");
        } catch (const DeidentifyError& e) {
            QVERIFY2(std::string(e.what()).find("burned-in") != std::string::npos, e.what());
        }
        QVERIFY(!fs::exists(root / "copy"));
    }

    // A real slice cut short inside its Pixel Data, and one padded with 7 zero
    // bytes: GDCM's whole read would allocate the declared length of the first,
    // and abort on the padding of the second. Refused, and copied.
    void truncatedPixelDataIsRefusedAndPaddingIsNot() {
        const fs::path source = dataPath("dcm_qa_ct/Philips_S21570/S2010");
        if (!fs::is_directory(source)) {
            QSKIP("the real DICOM data (../shared/data) is absent");
        }
        QTemporaryDir dir;
        const fs::path root = dir.path().toStdString();
        const fs::path cut = root / "cut.dcm";
        fs::copy_file(filesOf(source).front(), cut);
        fs::permissions(cut, fs::perms::owner_write, fs::perm_options::add);
        fs::resize_file(cut, fs::file_size(cut) - 1000);
        try {
            deidentifySeries({cut}, root / "copy");
            QFAIL("no error");
        } catch (const DeidentifyError& e) {
            QVERIFY2(std::string(e.what()).find("cut.dcm") != std::string::npos &&
                         std::string(e.what()).find("truncated pixel data") != std::string::npos,
                     e.what());
        }
        const fs::path padded = root / "padded.dcm";
        fs::copy_file(filesOf(source).front(), padded);
        fs::permissions(padded, fs::perms::owner_write, fs::perm_options::add);
        std::ofstream(padded, std::ios::binary | std::ios::app) << std::string(7, '\0');
        deidentifySeries({padded}, root / "copy");
        QCOMPARE(scanPath(root / "copy").series.size(), std::size_t(1));
    }

    void uidsMapConsistently() {
        Deidentifier d;
        const std::string a = d.replacementUid("1.2.3.4");
        QCOMPARE(d.replacementUid("1.2.3.4"), a);
        QVERIFY(d.replacementUid("1.2.3.5") != a);
        QVERIFY(a != "1.2.3.4");
        QVERIFY(a.size() <= 64);
        QVERIFY(a.find_first_not_of("0123456789.") == std::string::npos);
        QVERIFY(Deidentifier().replacementUid("1.2.3.4") != a); // a new mapping per copy
    }
};

QTEST_GUILESS_MAIN(TestDeidentifier)
#include "test_deidentifier.moc"
