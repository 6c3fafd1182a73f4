// A PET series as the workstation shows it (core/pet/PetDisplay.h, loadDisplayedSeries): on
// PET series made from a real CT with DCMTK, the values in SUVbw (the stored activity times
// the factor computed by hand), or in Bq/mL with the refusal naming the element; the unit,
// its UCUM code and the window that follow.
#include <QTemporaryDir>
#include <QTest>

#include <cmath>
#include <string>

#include "core/io/Catalog.h"
#include "core/io/DisplayedSeries.h"
#include "core/mpr/PlaneSampler.h"
#include "core/pet/PetDisplay.h"
#include "core/pet/SuvParameters.h"
#include "tests/support/PetFromCt.h"
#include "tests/support/RealData.h"

using namespace lucent;
using namespace lucent::test;

namespace {

const char* const kCt = "dcm_qa_ct/Philips_S21570/S2010";

// 75.5 kg, 370 MBq of 18F (half-life 6586.2 s), injected 3900 s before the scan (PetHeader).
double handFactor() {
    return 75500.0 / (370e6 * std::pow(2.0, -3900.0 / 6586.2));
}

bool near(double got, double want, double relative = 1e-6) {
    return std::abs(got - want) <= relative * std::max(std::abs(want), 1e-300);
}

SuvParameters validParameters() {
    SuvParameters p;
    p.units = "BQML";
    p.correctedImage = "ATTN\\DECY";
    p.decayCorrection = "START";
    p.patientWeightKg = 75.5;
    p.totalDoseBq = 370e6;
    p.halfLifeS = 6586.2;
    p.injectionTime = 1000.0;
    p.seriesTime = 4900.0;
    return p;
}

struct Loaded {
    PetSeries pet;
    SeriesEntry entry;
    Volume volume;
};

Loaded loadPet(const QTemporaryDir& dir, const PetHeader& header) {
    Loaded out;
    out.pet = writePetFromCt(kRealData / kCt, dir.path().toStdString(), header);
    const Catalog catalog = scanPath(dir.path().toStdString());
    if (catalog.series.size() != 1) {
        throw std::runtime_error("the PET copy is not one series");
    }
    out.entry = catalog.series.front();
    out.volume = loadDisplayedSeries(out.entry);
    return out;
}

// Every voxel checked equals the stored activity times `factor` (1e-6 relative); returns
// how many were not zero.
int checkValues(const Loaded& l, double factor) {
    int nonZero = 0;
    const int last = static_cast<int>(l.entry.slices.size()) - 1;
    for (const int k : {0, 9, last}) {
        const std::filesystem::path file = l.entry.slices[static_cast<std::size_t>(k)].file;
        for (const auto& [i, j] : {std::pair{256, 256}, {200, 300}, {100, 250}, {300, 120}}) {
            const double want = storedActivity(l.pet, file, i, j) * factor;
            const double got = l.volume.value(i, j, k);
            nonZero += want != 0.0 ? 1 : 0;
            if (!(near(got, want) || (want == 0.0 && got == 0.0))) {
                qWarning("slice %d (%d, %d): %g, by hand %g", k, i, j, got, want);
                return -1;
            }
        }
    }
    return nonZero;
}

} // namespace

class TestPetDisplay : public QObject {
    Q_OBJECT
private slots:
    void unitsAndRefusals() {
        const PetDisplay suv = petDisplayOf(validParameters());
        QVERIFY(suv.inSuv() && suv.refusal.empty());
        QVERIFY(near(suv.suvFactor, handFactor(), 1e-12));
        QCOMPARE(suv.unit(), std::string("SUVbw"));
        QCOMPARE(suv.ucum(), std::string("{SUVbw}g/ml"));
        QCOMPARE(petDisplayNotice(suv), std::string());

        SuvParameters p = validParameters();
        p.patientWeightKg.reset();
        const PetDisplay noWeight = petDisplayOf(p);
        QVERIFY(!noWeight.inSuv());
        QCOMPARE(noWeight.unit(), std::string("Bq/mL"));
        QCOMPARE(noWeight.ucum(), std::string("Bq/ml"));
        QCOMPARE(noWeight.refusal, std::string("PatientWeight (0010,1030) is missing"));
        QCOMPARE(petDisplayNotice(noWeight),
                 std::string("PT series shown in Bq/mL, not in SUVbw: PatientWeight (0010,1030) "
                             "is missing"));

        p = validParameters();
        p.units = "CNTS";
        const PetDisplay counts = petDisplayOf(p);
        QCOMPARE(counts.unit(), std::string("counts"));
        QCOMPARE(counts.ucum(), std::string("{counts}"));
        QVERIFY(counts.refusal.find("Units (0054,1001) is CNTS") != std::string::npos);
        // GML: already SUVbw, shown as stored.
        p.units = "GML";
        const PetDisplay gml = petDisplayOf(p);
        QVERIFY(gml.inSuv() && gml.suvFactor == 1.0 && gml.unit() == "SUVbw");
        p.units.clear();
        const PetDisplay none = petDisplayOf(p);
        QCOMPARE(none.unit(), std::string());
        QCOMPARE(none.ucum(), std::string("1"));
        QVERIFY(petDisplayNotice(none).find("shown in stored units") != std::string::npos);
    }

    // Through the loading path of the workstation (loadDisplayedSeries): SUVbw at every
    // voxel checked, the 0 to 6 SUV window.
    void petInSuv() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        const Loaded l = loadPet(dir, {});
        QVERIFY(l.volume.pet.has_value());
        QVERIFY(l.volume.pet->inSuv());
        QVERIFY(near(l.volume.pet->suvFactor, handFactor(), 1e-12));
        QCOMPARE(l.volume.pet->storedUnits, std::string("BQML"));
        QCOMPARE(l.volume.modality, std::string("PT"));
        QCOMPARE(l.volume.type(), VoxelType::Float32);
        QVERIFY(checkValues(l, handFactor()) >= 6);
        const WindowLevel window = defaultWindow(l.volume);
        QCOMPARE(window.center, 3.0);
        QCOMPARE(window.width, 6.0);
        QCOMPARE(window.step, 0.01);
    }

    // Without PatientWeight: Bq/mL as stored, the refusal naming the element, a window of
    // the data's own percentiles.
    void missingWeightStaysInBqPerMl() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        PetHeader header;
        header.patientWeight.clear();
        const Loaded l = loadPet(dir, header);
        QVERIFY(l.volume.pet.has_value());
        QVERIFY(!l.volume.pet->inSuv());
        QCOMPARE(l.volume.pet->unit(), std::string("Bq/mL"));
        QVERIFY2(l.volume.pet->refusal.find("PatientWeight (0010,1030)") != std::string::npos,
                 l.volume.pet->refusal.c_str());
        QVERIFY(checkValues(l, 1.0) >= 6);
        QVERIFY(defaultWindow(l.volume).width > 6.0);
    }

    // What is no PET is loaded as loadSeries loads it.
    void otherSeriesUntouched() {
        REQUIRE_DATA(kCt);
        const Catalog catalog = scanPath(kRealData / kCt);
        const Volume shown = loadDisplayedSeries(catalog.series.front());
        const Volume plain = loadSeries(catalog.series.front());
        QVERIFY(!shown.pet.has_value());
        QCOMPARE(shown.type(), plain.type());
        QVERIFY(std::equal(shown.bytes().begin(), shown.bytes().end(), plain.bytes().begin()));
    }
};

QTEST_GUILESS_MAIN(TestPetDisplay)
#include "test_pet_display.moc"
