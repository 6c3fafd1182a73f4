// Measurements as a DICOM SR (TID 1500) on real CT: every kind, on an acquired
// slice (SCOORD) and an oblique plane (SCOORD3D), written and read back equal;
// the file checked by dciodvfy; a foreign SR read read-only with what it could
// not show listed; broken files named in the error.
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <fstream>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmsr/dsrdoc.h>

#include "core/pet/SuvStatistics.h"
#include "core/report/MeasurementReport.h"
#include "tests/core/report/ForeignReport.h"
#include "tests/core/report/MeasuredSeries.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

// The items of the SR's content tree with this value type.
int countItems(const fs::path& file, DSRTypes::E_ValueType type) {
    DcmFileFormat f;
    DSRDocument doc;
    if (f.loadFile(file.c_str()).bad() || doc.read(*f.getDataset()).bad()) {
        return -1;
    }
    int n = 0;
    DSRDocumentTree& tree = doc.getTree();
    for (size_t node = tree.gotoRoot(); node != 0; node = tree.iterate()) {
        n += tree.getCurrentContentItem().getValueType() == type ? 1 : 0;
    }
    return n;
}

// The UCUM codes of the SR's numbers, with the concept and derivation (if any) of each:
// "SUVbw/Peak Value Within ROI {SUVbw}g/ml".
QStringList numberUnits(const fs::path& file) {
    DcmFileFormat f;
    DSRDocument doc;
    QStringList out;
    if (f.loadFile(file.c_str()).bad() || doc.read(*f.getDataset()).bad()) {
        return {"unreadable"};
    }
    DSRDocumentTree& tree = doc.getTree();
    for (size_t node = tree.gotoRoot(); node != 0; node = tree.iterate()) {
        DSRContentItem& item = tree.getCurrentContentItem();
        if (item.getValueType() != DSRTypes::VT_Num || item.getNumericValuePtr() == nullptr) {
            continue;
        }
        QString text = item.getConceptName().getCodeMeaning().c_str();
        const std::string unit =
            item.getNumericValuePtr()->getMeasurementUnit().getCodeValue().c_str();
        if (tree.gotoChild() != 0) {
            do {
                DSRContentItem& child = tree.getCurrentContentItem();
                if (child.getValueType() == DSRTypes::VT_Code &&
                    child.getConceptName().getCodeValue() == "121401") {
                    text += "/" + QString(child.getCodeValuePtr()->getCodeMeaning().c_str());
                }
            } while (tree.gotoNext() != 0);
            tree.gotoParent();
        }
        out << text + " " + QString::fromStdString(unit);
    }
    return out;
}

// dciodvfy's error lines ("Error - ..."), or a line saying it could not run.
QStringList dciodvfyErrors(const fs::path& file) {
    QProcess p;
    p.setProcessChannelMode(QProcess::MergedChannels);
    p.start("dciodvfy", {QString::fromStdString(file.string())});
    if (!p.waitForStarted(10000)) {
        return {"dciodvfy did not start: install dicom3tools (packaging/install-deps.sh)"};
    }
    p.waitForFinished(60000);
    QStringList errors;
    for (const QString& line : QString::fromUtf8(p.readAll()).split('\n')) {
        if (line.startsWith("Error")) {
            errors << line;
        }
    }
    return errors;
}

} // namespace

class TestMeasurementReport : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    Volume volume_;
    ReferencedSeries series_;

    // The SR as another viewer reads it: Lucent's exact geometry items and marker taken
    // out, the measurements come from the standard SCOORD or SCOORD3D and NUM items alone,
    // within 32-bit float precision, read-only, unlabelled ones under their kind's name.
    void readAsForeign(const fs::path& lucentFile, std::vector<Measurement> written) {
        DcmFileFormat f;
        QVERIFY(f.loadFile(lucentFile.c_str()).good());
        DSRDocument doc;
        QVERIFY(doc.read(*f.getDataset()).good());
        const DSRCodedEntryValue geometry("LUCENT-GEOMETRY", "99LUCENT",
                                          "Lucent measurement geometry");
        int removed = 0;
        while (doc.getTree().gotoNamedNode(geometry) > 0) {
            QVERIFY(doc.getTree().removeCurrentContentItem() > 0);
            ++removed;
        }
        QCOMPARE(removed, static_cast<int>(written.size()));
        QVERIFY(doc.setManufacturer("Other Viewer").good());
        DcmFileFormat out;
        QVERIFY(doc.write(*out.getDataset()).good());
        const fs::path file =
            lucentFile.parent_path() / ("foreign-" + lucentFile.filename().string());
        QVERIFY(out.saveFile(file.c_str(), EXS_LittleEndianExplicit).good());
        const ReadReport r = readMeasurementReport(file, &series_);
        QVERIFY(!r.writtenByLucent);
        QVERIFY2(r.notShown.empty(), r.notShown.empty() ? "" : r.notShown.front().c_str());
        for (Measurement& m : written) {
            m.label = m.label.empty() ? measurementKindName(m.kind) : m.label;
        }
        for (const Measurement& m : r.measurements) {
            QVERIFY(m.readOnly);
            // Drawn on a plane that holds it, for the views to show it on.
            QVERIFY2(distanceFromPlane(m, m.plane) < 1e-3, measurementKindName(m.kind));
            QVERIFY(std::abs(glm::dot(m.plane.u, m.plane.v)) < 1e-3);
        }
        test::compareMeasurements(r.measurements, written, 1e-3, false);
    }

    void roundTrip(const std::vector<Measurement>& written, bool acquired) {
        const fs::path file =
            fs::path(dir_.path().toStdString()) / (acquired ? "acq.dcm" : "obl.dcm");
        const WrittenReport w = writeMeasurementReport(file, series_, written);
        QCOMPARE(w.studyUid, series_.studyUid);
        QVERIFY(!w.sopInstanceUid.empty());
        const ReadReport r = readMeasurementReport(file, &series_);
        QVERIFY(r.writtenByLucent);
        QCOMPARE(r.sopInstanceUid, w.sopInstanceUid);
        QCOMPARE(r.referencedSeries, std::vector<std::string>{series_.seriesUid});
        QVERIFY2(r.notShown.empty(), r.notShown.empty() ? "" : r.notShown.front().c_str());
        test::compareMeasurements(r.measurements, written);
        // 7 regions (the bidirectional has two): 2D on the acquired slice, 3D on the oblique one.
        QCOMPARE(countItems(file, DSRTypes::VT_SCoord), acquired ? 7 : 0);
        QCOMPARE(countItems(file, DSRTypes::VT_SCoord3D), acquired ? 0 : 7);
        const QStringList errors = dciodvfyErrors(file);
        QVERIFY2(errors.isEmpty(), qPrintable(errors.join('\n')));
        readAsForeign(file, written);
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        volume_ = loadPath(test::kMeasuredSeriesDir);
        series_ = readReferencedSeries(test::seriesFiles());
        QCOMPARE(series_.images.size(), std::size_t(28));
        QVERIFY(!series_.frameOfReferenceUid.empty());
    }

    void acquiredSliceRoundTrip() {
        const SlicePlane plane = test::acquiredPlane(series_, 11);
        const std::vector<Measurement> m = test::everyKind(volume_, plane, "acquired");
        QVERIFY(m.back().statistics.samples > 100);
        QVERIFY(series_.acquiredImageOf(m.front()) == &series_.images[11]);
        roundTrip(m, true);
    }

    void obliquePlaneRoundTrip() {
        const std::vector<Measurement> m =
            test::everyKind(volume_, test::obliquePlane(volume_), "oblique");
        QVERIFY(series_.acquiredImageOf(m.front()) == nullptr);
        QVERIFY(m.back().statistics.samples > 100);
        roundTrip(m, false);
    }

    // An ellipse on a PET series in SUVbw: its statistics in {SUVbw}g/ml and SUVmax, SUVmean
    // and SUVpeak as the quantity SUVbw with its derivation (CID 7464), read back by Lucent
    // (exact) and from the numbers alone (another viewer's SR). The CT's values stand in
    // for SUVs: what is written does not depend on where they came from.
    void suvEllipseRoundTrip() {
        std::vector<Measurement> m =
            test::everyKind(volume_, test::acquiredPlane(series_, 9), "pet");
        Measurement& ellipse = m.back();
        ellipse.unit = "SUVbw";
        ellipse.suv = suvStatistics(volume_, ellipseSuvRegion(volume_.geometry(), ellipse.plane,
                                                              measurementEllipse(ellipse)));
        QVERIFY(ellipse.suv->voxels > 100);
        QVERIFY(ellipse.suv->peak < ellipse.suv->max);
        roundTrip(m, true);
        const fs::path file = fs::path(dir_.path().toStdString()) / "acq.dcm";
        const QStringList units = numberUnits(file);
        for (const char* expected : {"SUVbw/Maximum {SUVbw}g/ml", "SUVbw/Mean {SUVbw}g/ml",
                                     "SUVbw/Peak Value Within ROI {SUVbw}g/ml", "Mean {SUVbw}g/ml",
                                     "Standard Deviation {SUVbw}g/ml", "Area mm2"}) {
            QVERIFY2(units.contains(expected), qPrintable(units.join('\n')));
        }
        // Stored units: Bq/mL as CID 84 writes it, no SUVs.
        ellipse.unit = "Bq/mL";
        ellipse.suv.reset();
        roundTrip(m, true);
        QVERIFY2(numberUnits(file).contains("Mean Bq/ml"),
                 qPrintable(numberUnits(file).join('\n')));
    }

    // An Enhanced MR multi-frame object: no single-frame image to put a SCOORD on, so
    // every region is 3D; the statistics have no unit.
    void enhancedMultiFrameGoesIn3D() {
        REQUIRE_DATA("dcm_qa_enh/Philips_IM_0027_fMAP.dcm");
        const fs::path mr = test::kRealData / "dcm_qa_enh/Philips_IM_0027_fMAP.dcm";
        const Volume volume = loadPath(mr);
        const ReferencedSeries series = readReferencedSeries({mr});
        QCOMPARE(series.images.size(), std::size_t(1));
        QVERIFY(series.images[0].frames > 1);
        const VolumeGeometry& g = volume.geometry();
        SlicePlane plane = standardPlane(g, Orientation::Axial,
                                         g.toPatient(0.5 * (glm::dvec3(g.dims) - 1.0)), 64, 64);
        std::vector<Measurement> written = test::everyKind(volume, plane, "mr");
        for (Measurement& m : written) {
            m.unit = "";
        }
        const fs::path file = fs::path(dir_.path().toStdString()) / "mr.dcm";
        writeMeasurementReport(file, series, written);
        QCOMPARE(countItems(file, DSRTypes::VT_SCoord), 0);
        QCOMPARE(countItems(file, DSRTypes::VT_SCoord3D), 7);
        const ReadReport r = readMeasurementReport(file, &series);
        test::compareMeasurements(r.measurements, written);
        const QStringList errors = dciodvfyErrors(file);
        QVERIFY2(errors.isEmpty(), qPrintable(errors.join('\n')));
    }

    void readOnlyAndIncompleteAreLeftOut() {
        std::vector<Measurement> m = test::everyKind(volume_, test::acquiredPlane(series_, 3), "x");
        m[0].readOnly = true;
        m[1].points.pop_back();
        const fs::path file = fs::path(dir_.path().toStdString()) / "partial.dcm";
        writeMeasurementReport(file, series_, m);
        const ReadReport r = readMeasurementReport(file, &series_);
        QCOMPARE(r.measurements.size(), m.size() - 2);
    }

    // An SR another program wrote with DCMTK's TID 1500 classes: a length on an
    // image, a volume Lucent has no kind for, and a finding code.
    void foreignReportIsReadOnly() {
        const ReferencedImage& image = series_.images[5];
        const fs::path file = fs::path(dir_.path().toStdString()) / "foreign.dcm";
        test::writeForeignReport(file, series_, image);

        const ReadReport r = readMeasurementReport(file, &series_);
        QVERIFY(!r.writtenByLucent);
        QCOMPARE(r.measurements.size(), std::size_t(1));
        const Measurement& m = r.measurements.front();
        QVERIFY(m.readOnly);
        QVERIFY(m.kind == MeasurementKind::Distance);
        QCOMPARE(m.label, std::string("Nodule A"));
        QVERIFY(glm::distance(m.points[0], image.patientPoint({100.5, 200.25})) < 1e-9);
        // (column, row) from the top-left corner of the top-left pixel.
        const glm::dvec3 expected = image.position +
                                    (140.0 - 0.5) * image.spacing.x * image.rowDir +
                                    (180.75 - 0.5) * image.spacing.y * image.colDir;
        QVERIFY(glm::distance(m.points[1], expected) < 1e-9);
        QVERIFY(std::abs(glm::dot(m.points[0] - image.position, image.normal())) < 1e-9);
        QString notShown = QString::fromStdString(r.notShown.empty() ? "" : r.notShown[0]);
        for (std::size_t i = 1; i < r.notShown.size(); ++i) {
            notShown += "\n" + QString::fromStdString(r.notShown[i]);
        }
        QVERIFY2(notShown.contains("Nodule A: Volume 2.5 cm3"), qPrintable(notShown));
        QVERIFY2(notShown.contains("Nodule A: Finding = Nodule"), qPrintable(notShown));
    }

    void brokenFilesAreNamed() {
        const fs::path text = fs::path(dir_.path().toStdString()) / "notes.txt";
        std::ofstream(text) << "not DICOM";
        try {
            readMeasurementReport(text);
            QFAIL("read a text file as an SR");
        } catch (const ReportError& e) {
            QVERIFY2(QString(e.what()).contains("notes.txt") &&
                         QString(e.what()).contains("not a DICOM"),
                     e.what());
        }
        const fs::path image = series_.images.front().file;
        try {
            readMeasurementReport(image);
            QFAIL("read a CT image as an SR");
        } catch (const ReportError& e) {
            QVERIFY2(QString(e.what()).contains(QString::fromStdString(image.string())) &&
                         QString(e.what()).contains("not a structured report"),
                     e.what());
        }
        // An SR, but a plain text report.
        DSRDocument textReport(DSRTypes::DT_BasicTextSR);
        QVERIFY(textReport.getTree().addContentItem(DSRTypes::RT_isRoot, DSRTypes::VT_Container) >
                0);
        QVERIFY(textReport.getTree()
                    .getCurrentContentItem()
                    .setConceptName(DSRCodedEntryValue("11528-7", "LN", "Radiology Report"))
                    .good());
        QVERIFY(textReport.getTree()
                    .addChildContentItem(DSRTypes::RT_contains, DSRTypes::VT_Text,
                                         DSRCodedEntryValue("121071", "DCM", "Finding"))
                    .good());
        QVERIFY(textReport.getTree().getCurrentContentItem().setStringValue("No findings.").good());
        DcmFileFormat textFile;
        QVERIFY(textReport.write(*textFile.getDataset()).good());
        const fs::path report = fs::path(dir_.path().toStdString()) / "report.dcm";
        QVERIFY(textFile.saveFile(report.c_str(), EXS_LittleEndianExplicit).good());
        try {
            readMeasurementReport(report);
            QFAIL("read a text report as a measurement report");
        } catch (const ReportError& e) {
            QVERIFY2(QString(e.what()).contains("report.dcm") &&
                         QString(e.what()).contains("not a TID 1500 Measurement Report") &&
                         QString(e.what()).contains("Radiology Report"),
                     e.what());
        }

        // An SR cut short: the first 3 KiB of a written one.
        const fs::path whole = fs::path(dir_.path().toStdString()) / "whole.dcm";
        writeMeasurementReport(whole, series_,
                               test::everyKind(volume_, test::acquiredPlane(series_, 2), "c"));
        std::ifstream in(whole, std::ios::binary);
        std::string bytes(3072, '\0');
        in.read(bytes.data(), 3072);
        const fs::path cut = fs::path(dir_.path().toStdString()) / "cut.dcm";
        std::ofstream(cut, std::ios::binary) << bytes;
        try {
            readMeasurementReport(cut);
            QFAIL("read a truncated SR");
        } catch (const ReportError& e) {
            QVERIFY2(QString(e.what()).contains("cut.dcm"), e.what());
        }
    }
};

QTEST_GUILESS_MAIN(TestMeasurementReport)
#include "test_measurement_report.moc"
