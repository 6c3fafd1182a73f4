// Lesions tracked over two real CT studies of one patient in a real study store
// (tests/core/followup/TwoStudies.h). Measurements marked target, non-target and lymph node are
// saved as Lucent's SRs, read back with their tracking UIDs and roles (exact geometry too),
// gathered into the RECIST table, which is checked against sums computed here from the points, and
// printed by `lucent-cli measurements --patient ID --recist [--json]`.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QTest>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmsr/cmr/tid1500.h>
#include <dcmtk/dcmsr/codes/dcm.h>
#include <dcmtk/dcmsr/dsrdoc.h>

#include "core/followup/FollowUpCollection.h"
#include "core/followup/FollowUpText.h"
#include "tests/core/followup/TwoStudies.h"
#include "tests/support/CliRunner.h"

using namespace lucent;
namespace fs = std::filesystem;
using namespace lucent::test;

namespace {

// A TID 1500 SR as another program writes one: a length "Node B" on `image`, its tracking
// UID, the RECIST category Target and the finding site Lymph node in SRT's older codes.
bool writeForeignLesion(const fs::path& file, const ReferencedSeries& series,
                        const ReferencedImage& image, const std::string& trackingUid) {
    TID1500_MeasurementReport report(CMR_CID7021::ImagingMeasurementReport);
    report.setLanguage(CID5000_Languages::English);
    report.getObservationContext().addPersonObserver("Other^Reader");
    report.addProcedureReported(CMR_CID100::ImagingProcedure);
    report.addIndividualMeasurements();
    auto& group = report.getIndividualMeasurements();
    group.setTrackingIdentifier("Node B");
    group.setTrackingUniqueIdentifier(trackingUid.c_str());
    group.addFindingSite(DSRCodedEntryValue("T-C4000", "SRT", "Lymph node"));
    using Value = CMR_TID1501_in_TID1500::MeasurementValue;
    group.addMeasurement(CMR_CID7469::Length, Value("12.5", CMR_CID7181::Millimeter));
    DSRSpatialCoordinatesValue line(DSRTypes::GT_Polyline);
    line.getGraphicDataList().addItem(100.5f, 200.25f);
    line.getGraphicDataList().addItem(120.5f, 200.25f);
    group.getMeasurement().addSpatialCoordinates(
        CODE_DCM_ImageRegion, line,
        DSRImageReferenceValue(image.sopClassUid, image.sopInstanceUid));
    group.addQualitativeEvaluation(
        DSRCodedEntryValue("112016", "DCM", "Baseline Category"),
        DSRCodedEntryValue("112074", "DCM", "Target Lesion at Baseline"));
    DSRDocument doc(DSRTypes::DT_Comprehensive3DSR);
    doc.createNewSeriesInStudy(series.studyUid.c_str());
    if (doc.setTreeFromRootTemplate(report).bad()) {
        return false;
    }
    doc.setManufacturer("Other Vendor");
    doc.getCurrentRequestedProcedureEvidence().addItem(
        series.studyUid.c_str(), series.seriesUid.c_str(), image.sopClassUid.c_str(),
        image.sopInstanceUid.c_str());
    DcmFileFormat out;
    return doc.write(*out.getDataset()).good() &&
           out.saveFile(file.c_str(), EXS_LittleEndianExplicit).good();
}

} // namespace

class TestFollowUpStore : public QObject {
    Q_OBJECT

    QTemporaryDir dir_;
    std::unique_ptr<StudyStore> store_;
    TwoStudies studies_;

    QString storeDir() const { return dir_.path() + "/store"; }

private slots:
    void initTestCase() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2020");
        store_ = std::make_unique<StudyStore>(storeDir().toStdString());
        makeTwoStudies(dir_.path().toStdString(), *store_, studies_);
    }

    // Read back by a fresh archive: the exact geometry, and each lesion's tracking UID,
    // role and lymph-node flag; the plain measurement got a tracking UID of its own,
    // kept from then on.
    void readBackWithTrackingUids() {
        MeasurementArchive archive(*store_);
        std::vector<Measurement> prior = archive.load(studies_.prior.seriesUid).measurements;
        compareMeasurements(prior, studies_.priorMeasurements, 1e-6, false);
        for (std::size_t i = 0; i < 3; ++i) {
            QVERIFY(prior[i].lesion == studies_.priorMeasurements[i].lesion);
        }
        QCOMPARE(prior[3].lesion.role, LesionRole::None);
        QVERIFY(!prior[3].lesion.trackingUid.empty());
        const std::vector<Measurement> current =
            archive.load(studies_.current.seriesUid).measurements;
        QCOMPARE(current.size(), studies_.currentMeasurements.size());
        for (std::size_t i = 0; i < 4; ++i) {
            QVERIFY(current[i].lesion == studies_.currentMeasurements[i].lesion);
        }
        QCOMPARE(current[0].lesion.trackingUid, prior[0].lesion.trackingUid); // one lesion

        const std::string plainUid = prior[3].lesion.trackingUid;
        archive.save(studies_.prior.seriesUid, prior);
        QCOMPARE(MeasurementArchive(*store_)
                     .load(studies_.prior.seriesUid)
                     .measurements[3]
                     .lesion.trackingUid,
                 plainUid);
    }

    // Another program's SR: its tracking UID, Target and the SRT lymph node read too.
    void foreignReportLesion() {
        const fs::path file = fs::path(dir_.path().toStdString()) / "foreign.dcm";
        const std::string uid = newDicomUid();
        QVERIFY(writeForeignLesion(file, studies_.current, studies_.current.images[70], uid));
        const ReadReport read = readMeasurementReport(file, &studies_.current);
        QCOMPARE(read.measurements.size(), std::size_t(1));
        const Measurement& m = read.measurements[0];
        QVERIFY(m.readOnly);
        QCOMPARE(m.label, std::string("Node B"));
        QCOMPARE(m.lesion.trackingUid, uid);
        QCOMPARE(m.lesion.role, LesionRole::Target);
        QVERIFY(m.lesion.lymphNode);
        QVERIFY2(read.notShown.empty(), read.notShown.empty() ? "" : read.notShown[0].c_str());
    }

    // The table from the store, against the same by hand: baseline = 2014-02-06.
    void recistTableFromTheStore() {
        const FollowUpSources sources = collectFollowUp(*store_, kPatient);
        QVERIFY(sources.problems.empty());
        QCOMPARE(sources.timepoints.size(), std::size_t(2));
        const FollowUpTable t = assessRecist(sources.timepoints);
        QCOMPARE(t.timepoints[0].studyDate, std::string("20140206"));
        QCOMPARE(t.timepoints[1].studyDate, std::string("20150206"));

        const auto& p = studies_.priorMeasurements;
        const auto& c = studies_.currentMeasurements;
        // Liver by its long axis, the node by its short axis.
        const double baseline = bidirectionalLongAxisMm(p[0]) + bidirectionalShortAxisMm(p[1]);
        const double followUp = measurementLengthMm(c[0]) + bidirectionalShortAxisMm(c[1]);
        QVERIFY(std::abs(t.timepoints[0].sumMm - baseline) < 1e-6);
        QVERIFY(std::abs(t.timepoints[1].sumMm - followUp) < 1e-6);
        QVERIFY(std::abs(*t.timepoints[1].fromBaselinePercent -
                         (followUp - baseline) / baseline * 100.0) < 1e-6);
        QVERIFY(std::abs(*t.timepoints[1].fromNadirPercent -
                         (followUp - baseline) / baseline * 100.0) < 1e-6);
        QCOMPARE(t.timepoints[1].response, RecistResponse::PD); // "New 1"
        QCOMPARE(t.timepoints[1].reasons.at(0), std::string("new lesion: New 1"));

        QCOMPARE(t.lesions.size(), std::size_t(4));
        const LesionRow& liver = t.lesions[0];
        QCOMPARE(liver.trackingUid, studies_.liver);
        QCOMPARE(liver.at[0]->where.seriesUid, studies_.prior.seriesUid);
        QCOMPARE(liver.at[1]->where.seriesUid, studies_.current.seriesUid);
        QVERIFY(glm::distance(liver.at[0]->where.centre, centreOf(p[0])) < 1e-6);
        QVERIFY(glm::distance(liver.at[1]->where.centre, centreOf(c[0])) < 1e-6);
        QVERIFY(t.lesions[1].lymphNode);
        QCOMPARE(t.lesions[2].name, std::string("Bone 1"));
        QCOMPARE(formatLesionCell(t.lesions[2], t.lesions[2].at[1]), std::string("present"));
        QCOMPARE(t.lesions[3].firstTimepoint, std::size_t(1));

        try {
            collectFollowUp(*store_, "NOBODY");
            QFAIL("a table of a patient the store does not hold");
        } catch (const StoreError& e) {
            QVERIFY2(QString(e.what()).contains("NOBODY"), e.what());
        }
    }

    void commandLine() {
        const FollowUpTable t = assessRecist(collectFollowUp(*store_, kPatient).timepoints);
        CliRun run =
            runCli({"measurements", "--patient", kPatient, "--store", storeDir(), "--recist"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        QVERIFY2(run.out.contains(QString::fromStdString(followUpText(t))), qPrintable(run.out));
        QVERIFY2(run.out.contains("2 timepoint(s), 4 tracked lesion(s)"), qPrintable(run.out));
        char sum[32];
        std::snprintf(sum, sizeof sum, "%.1f", t.timepoints[1].sumMm);
        QVERIFY2(run.out.contains(QRegularExpression("Sum of diameters \\(mm\\) +[0-9.]+ +" +
                                                     QRegularExpression::escape(sum))),
                 qPrintable(run.out));
        QVERIFY2(run.out.contains(QRegularExpression("Response +Baseline +PD")),
                 qPrintable(run.out));

        run = runCli(
            {"measurements", "--patient", kPatient, "--store", storeDir(), "--recist", "--json"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const QJsonObject json = QJsonDocument::fromJson(run.out.toUtf8()).object();
        const QJsonArray timepoints = json["timepoints"].toArray();
        QCOMPARE(timepoints.size(), 2);
        QCOMPARE(timepoints[0].toObject()["study_date"].toString(), QString("2014-02-06"));
        const QJsonObject followUp = timepoints[1].toObject();
        QCOMPARE(followUp["response"].toString(), QString("PD"));
        QVERIFY(std::abs(followUp["sum_mm"].toDouble() - t.timepoints[1].sumMm) < 1e-9);
        QVERIFY(std::abs(followUp["change_from_baseline_percent"].toDouble() -
                         *t.timepoints[1].fromBaselinePercent) < 1e-9);
        const QJsonObject liver = json["lesions"].toArray()[0].toObject();
        QCOMPARE(liver["tracking_uid"].toString(), QString::fromStdString(studies_.liver));
        QCOMPARE(liver["timepoints"].toArray()[1].toObject()["series_uid"].toString(),
                 QString::fromStdString(studies_.current.seriesUid));
        QVERIFY(json["lesions"].toArray()[3].toObject()["new_lesion"].toBool());

        QCOMPARE(runCli({"measurements", "--recist", "--store", storeDir()}).exitCode, 2);
        run = runCli({"measurements", "--patient", "NOBODY", "--store", storeDir(), "--recist"});
        QCOMPARE(run.exitCode, 3);
        QVERIFY2(run.err.contains("NOBODY"), qPrintable(run.err));
    }

    void cleanupTestCase() { store_.reset(); }
};

QTEST_GUILESS_MAIN(TestFollowUpStore)
#include "test_followup_store.moc"
