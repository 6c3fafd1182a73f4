// SUVbw (core/pet) on PET series made from a real CT with DCMTK: the factor and voxel SUVs
// against a hand computation, the scan time rule (series time unless after the earliest
// acquisition), and every refusal naming its DICOM element.
#include <QTemporaryDir>
#include <QTest>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include "core/io/Catalog.h"
#include "core/dicom/PetSuvReader.h"
#include "core/pet/SuvStatistics.h"
#include "tests/support/PetFromCt.h"
#include "tests/support/RealData.h"

using namespace lucent;
using namespace lucent::test;

namespace {

const char* const kCt = "dcm_qa_ct/Philips_S21570/S2010";

// 75.5 kg, 370 MBq of 18F (half-life 6586.2 s) injected `dt` seconds before the scan.
double handFactor(double dt) {
    return 75500.0 / (370e6 * std::pow(2.0, -dt / 6586.2));
}

bool near(double got, double want, double relative = 1e-6) {
    return std::abs(got - want) <= relative * std::max(std::abs(want), 1e-300);
}

// The message suvBwFactor throws, or "" when it computes.
std::string refusal(const SuvParameters& p) {
    try {
        suvBwFactor(p);
    } catch (const SuvError& e) {
        return e.what();
    }
    return {};
}

// The stored value of pixel (i, j) of a 16-bit file, read with DCMTK (12 bits stored).
int storedValue(const std::filesystem::path& file, int i, int j) {
    DcmFileFormat dicom;
    const Uint16* pixels = nullptr;
    Uint16 columns = 0;
    if (dicom.loadFile(file.c_str()).bad() ||
        dicom.getDataset()->findAndGetUint16(DCM_Columns, columns).bad() ||
        dicom.getDataset()->findAndGetUint16Array(DCM_PixelData, pixels).bad()) {
        return -1;
    }
    return pixels[static_cast<std::size_t>(j) * columns + static_cast<std::size_t>(i)] & 0x0fff;
}

} // namespace

class TestSuv : public QObject {
    Q_OBJECT
private slots:
    void dicomTimes() {
        QCOMPARE(*dicomDateTimeSeconds("19700102", "010203.5"), 86400.0 + 3723.5);
        QCOMPARE(*dicomDateTimeSeconds("1970.01.02", "01:02:03"), 86400.0 + 3723.0);
        QCOMPARE(*dicomDateTimeSeconds("19700101", "01"), 3600.0);
        QCOMPARE(*dicomDtSeconds("19700102010203.25+0100"), 86400.0 + 3723.25);
        QCOMPARE(*dicomDtSeconds("19700102"), 86400.0);
        QVERIFY(!dicomDateTimeSeconds("20150230", "093500"));
        QVERIFY(!dicomDateTimeSeconds("20150206", "253500"));
        QVERIFY(!dicomDateTimeSeconds("", "093500"));
        QVERIFY(!dicomDtSeconds("2015"));
    }

    // The rule without files: the series time, unless after the earliest acquisition.
    void scanReferenceRule() {
        SuvParameters p;
        p.seriesTime = 1000.0;
        p.earliestAcquisitionTime = 1200.0;
        QCOMPARE(suvScanReferenceTime(p), 1000.0);
        p.seriesTime = 1300.0;
        QCOMPARE(suvScanReferenceTime(p), 1200.0);
        p.seriesTime.reset();
        QCOMPARE(suvScanReferenceTime(p), 1200.0);
        p.earliestAcquisitionTime.reset();
        QVERIFY_THROWS_EXCEPTION(SuvError, suvScanReferenceTime(p));
    }

    // Injected 08:30:00, series and first acquisition 09:35:00: dt = 3900 s. Each image has
    // its own slope, so Bq/mL = stored * slope of that image.
    void suvAtVoxelsByHand() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        const PetSeries pet = writePetFromCt(kRealData / kCt, dir.path().toStdString(), {});
        const double factor = suvBwFactor(readSuvParameters(pet.files));
        QVERIFY2(near(factor, handFactor(3900.0), 1e-12), qPrintable(QString::number(factor)));

        const Catalog catalog = scanPath(dir.path().toStdString());
        QCOMPARE(catalog.series.size(), std::size_t(1));
        const SeriesEntry& entry = catalog.series[0];
        QCOMPARE(entry.modality, std::string("PT"));
        const Volume suv = suvVolume(loadSeries(entry), factor);
        QCOMPARE(suv.type(), VoxelType::Float32);
        int nonZero = 0;
        for (const int k : {0, 7, static_cast<int>(entry.slices.size()) - 1}) {
            const std::filesystem::path file = entry.slices[static_cast<std::size_t>(k)].file;
            const auto n = std::find(pet.files.begin(), pet.files.end(), file) - pet.files.begin();
            QVERIFY(n < static_cast<long>(pet.files.size()));
            for (const auto& [i, j] : {std::pair{256, 256}, {200, 300}, {100, 250}, {0, 0}}) {
                const int stored = storedValue(file, i, j);
                QVERIFY(stored >= 0);
                nonZero += stored > 0 ? 1 : 0;
                const double want =
                    stored * pet.slopes[static_cast<std::size_t>(n)] * handFactor(3900.0);
                const double got = suv.value(i, j, k);
                QVERIFY2(near(got, want) || (want == 0.0 && got == 0.0),
                         qPrintable(QString("slice %1 (%2, %3): %4, by hand %5")
                                        .arg(k)
                                        .arg(i)
                                        .arg(j)
                                        .arg(got)
                                        .arg(want)));
            }
        }
        QVERIFY(nonZero >= 6);
    }

    // The series time 09:40:00 is after the first acquisition (09:35:00): QIBA's rule takes
    // the earliest acquisition, over the whole series; one file alone knows only its own.
    void seriesTimeAfterAcquisition() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        PetHeader h;
        h.seriesTime = "094000";
        const PetSeries pet = writePetFromCt(kRealData / kCt, dir.path().toStdString(), h);
        QVERIFY(near(suvBwFactor(readSuvParameters(pet.files)), handFactor(3900.0), 1e-12));
        // The fifth image alone: acquired 09:37:00, before its series time.
        QVERIFY(near(suvBwFactor(readSuvParameters(pet.files[4])), handFactor(4020.0), 1e-12));
        // A series time before every acquisition is the reference (as Slicer takes it).
        h.seriesTime = "093000";
        QTemporaryDir dir2;
        const PetSeries early = writePetFromCt(kRealData / kCt, dir2.path().toStdString(), h);
        QVERIFY(near(suvBwFactor(readSuvParameters(early.files)), handFactor(3600.0), 1e-12));
    }

    // RadiopharmaceuticalStartDateTime wins over StartTime.
    void startDateTimePreferred() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        PetHeader h;
        h.startDateTime = "20150206082000";
        const PetSeries pet = writePetFromCt(kRealData / kCt, dir.path().toStdString(), h);
        QVERIFY(near(suvBwFactor(readSuvParameters(pet.files.front())), handFactor(4500.0), 1e-12));
    }

    void refusals_data() {
        QTest::addColumn<QString>("field");
        QTest::addColumn<QString>("value");
        QTest::addColumn<QString>("message");
        QTest::newRow("CNTS") << "units"
                              << "CNTS"
                              << "Units (0054,1001) is CNTS";
        QTest::newRow("GML") << "units"
                             << "GML"
                             << "Units (0054,1001) is GML: the values are "
                                "already SUVbw";
        QTest::newRow("no weight") << "weight"
                                   << ""
                                   << "PatientWeight (0010,1030) is missing";
        QTest::newRow("zero weight") << "weight"
                                     << "0"
                                     << "PatientWeight (0010,1030) is 0";
        QTest::newRow("negative decay time") << "start"
                                             << "100000"
                                             << "(0018,1072/1078) is 1500 s after the scan "
                                                "reference, SeriesDate/SeriesTime";
        QTest::newRow("no dose") << "dose"
                                 << ""
                                 << "RadionuclideTotalDose (0018,1074) is missing";
        QTest::newRow("no half-life") << "halfLife"
                                      << ""
                                      << "RadionuclideHalfLife (0018,1075) is missing";
        QTest::newRow("no DECY") << "corrected"
                                 << "ATTN"
                                 << "CorrectedImage (0028,0051) is ATTN: it lacks DECY";
        QTest::newRow("no ATTN") << "corrected"
                                 << "DECY\\NORM"
                                 << "it lacks ATTN";
        QTest::newRow("no CorrectedImage") << "corrected"
                                           << ""
                                           << "CorrectedImage (0028,0051) is missing";
        QTest::newRow("ADMIN") << "decay"
                               << "ADMIN"
                               << "DecayCorrection (0054,1102) is ADMIN";
        QTest::newRow("no start time") << "start"
                                       << ""
                                       << "(0018,1072) are missing";
    }

    void refusals() {
        REQUIRE_DATA(kCt);
        QFETCH(QString, field);
        QFETCH(QString, value);
        QFETCH(QString, message);
        PetHeader h;
        std::string* target = field == "units"       ? &h.units
                              : field == "weight"    ? &h.patientWeight
                              : field == "start"     ? &h.startTime
                              : field == "dose"      ? &h.totalDose
                              : field == "halfLife"  ? &h.halfLife
                              : field == "corrected" ? &h.correctedImage
                                                     : &h.decayCorrection;
        *target = value.toStdString();
        QTemporaryDir dir;
        const PetSeries pet = writePetFromCt(kRealData / kCt, dir.path().toStdString(), h);
        const std::string why = refusal(readSuvParameters(pet.files));
        QVERIFY2(why.find(message.toStdString()) != std::string::npos, why.c_str());
    }
};

QTEST_GUILESS_MAIN(TestSuv)
#include "test_suv.moc"
