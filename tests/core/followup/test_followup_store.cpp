// Lesions tracked over two real CT studies of one patient in a real study store: the
// Philips phantom's 5 mm series made a prior study (new study, series and instance UIDs,
// an earlier date, by DCMTK's dcmodify on copies) and its 1 mm series as the follow-up.
// Measurements marked target, non-target and lymph node are saved as Lucent's SRs, read
// back with their tracking UIDs and roles (exact geometry too), gathered into the RECIST
// table, which is checked against sums computed here from the points, and printed by
// `lucent-cli measurements --patient ID --recist [--json]`.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmsr/cmr/tid1500.h>
#include <dcmtk/dcmsr/codes/dcm.h>
#include <dcmtk/dcmsr/dsrdoc.h>

#include "core/followup/FollowUpCollection.h"
#include "core/followup/FollowUpText.h"
#include "core/report/MeasurementArchive.h"
#include "core/report/MeasurementReport.h"
#include "tests/core/report/MeasuredSeries.h"
#include "tests/support/CliRunner.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

const fs::path kFollowUpDir = test::kRealData / "dcm_qa_ct/Philips_S21570/S2020";
const char* kPatient = "PLASTIC"; // the phantom's Patient ID

std::vector<fs::path> filesIn(const fs::path& folder) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(folder)) {
        if (e.is_regular_file() && e.path().filename() != "LICENSE") {
            files.push_back(e.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::string tag(DcmItem& d, const DcmTagKey& key) {
    OFString v;
    d.findAndGetOFString(key, v);
    return v.c_str();
}

// Stores a file as a retrieval would, with the index facts read from its header.
bool store(StudyStore& store, const fs::path& file) {
    DcmFileFormat f;
    if (f.loadFile(file.c_str(), EXS_Unknown, EGL_noChange, 4096).bad()) {
        return false;
    }
    DcmDataset& d = *f.getDataset();
    InstanceRecord r;
    r.series = {tag(d, DCM_SeriesInstanceUID), tag(d, DCM_StudyInstanceUID), tag(d, DCM_Modality),
                tag(d, DCM_SeriesDescription), tag(d, DCM_PatientName),      tag(d, DCM_PatientID),
                tag(d, DCM_StudyDate)};
    r.sopInstanceUid = tag(d, DCM_SOPInstanceUID);
    const fs::path temp = store.temporaryFile();
    fs::copy_file(file, temp);
    return store.add(temp, r);
}

Measurement lesion(MeasurementKind kind, const SlicePlane& plane, std::vector<glm::dvec2> pixels,
                   const std::string& label, LesionRole role, bool node, const std::string& uid) {
    Measurement m;
    m.kind = kind;
    m.plane = plane;
    for (const glm::dvec2& p : pixels) {
        m.points.push_back(plane.pointAt(p.x, p.y));
    }
    m.label = label;
    m.lesion = {role, node, uid};
    return m;
}

glm::dvec3 centreOf(const Measurement& m) {
    glm::dvec3 c(0.0);
    for (const glm::dvec3& p : m.points) {
        c += p / static_cast<double>(m.points.size());
    }
    return c;
}

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
    ReferencedSeries prior_, current_;
    std::vector<Measurement> priorMeasurements_, currentMeasurements_;
    const std::string liver_ = newDicomUid(), node_ = newDicomUid(), bone_ = newDicomUid(),
                      newLesion_ = newDicomUid();

    QString storeDir() const { return dir_.path() + "/store"; }

private slots:
    void initTestCase() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2020");
        // The prior: the 5 mm series as another study a year earlier.
        const fs::path priorDir = fs::path(dir_.path().toStdString()) / "prior";
        fs::create_directories(priorDir);
        QStringList args{"-nb", "-gin",
                         "-m",  "StudyDate=20140206",
                         "-m",  QString("StudyInstanceUID=%1").arg(newDicomUid().c_str()),
                         "-m",  QString("SeriesInstanceUID=%1").arg(newDicomUid().c_str())};
        for (const fs::path& file : test::seriesFiles()) {
            const fs::path copy = priorDir / file.filename();
            fs::copy_file(file, copy);
            fs::permissions(copy, fs::perms::owner_write, fs::perm_options::add);
            args << QString::fromStdString(copy.string());
        }
        QProcess modify;
        modify.start("dcmodify", args);
        QVERIFY2(modify.waitForFinished(60000) && modify.exitCode() == 0,
                 modify.readAllStandardError().constData());

        store_ = std::make_unique<StudyStore>(storeDir().toStdString());
        for (const fs::path& file : filesIn(priorDir)) {
            QVERIFY(store(*store_, file));
        }
        for (const fs::path& file : filesIn(kFollowUpDir)) {
            QVERIFY(store(*store_, file));
        }
        prior_ = readReferencedSeries(filesIn(priorDir));
        current_ = readReferencedSeries(filesIn(kFollowUpDir));
        QVERIFY(prior_.studyUid != current_.studyUid);

        const SlicePlane before = test::acquiredPlane(prior_, 14);
        using K = MeasurementKind;
        using R = LesionRole;
        priorMeasurements_ = {
            lesion(K::Bidirectional, before, {{200, 300}, {251.5, 310}, {224, 290}, {226, 322.25}},
                   "Liver 1", R::Target, false, liver_),
            lesion(K::Bidirectional, before, {{300, 200}, {340, 204}, {318, 190}, {319, 219.5}},
                   "Node 1", R::Target, true, node_),
            lesion(K::Distance, before, {{100, 100}, {130, 110}}, "Bone 1", R::NonTarget, false,
                   bone_),
            lesion(K::Distance, before, {{50, 50}, {90, 60}}, "plain", R::None, false, ""),
        };
        const SlicePlane after = test::acquiredPlane(current_, 70);
        currentMeasurements_ = {
            lesion(K::Distance, after, {{200, 300}, {258.25, 312}}, "Liver 1", R::Target, false,
                   liver_),
            lesion(K::Bidirectional, after, {{300, 200}, {345, 205}, {318, 188}, {320, 224.75}},
                   "Node 1", R::Target, true, node_),
            lesion(K::Arrow, after, {{140, 140}, {120, 110}}, "Bone 1", R::NonTarget, false, bone_),
            lesion(K::Distance, after, {{400, 380}, {420, 392}}, "New 1", R::NonTarget, false,
                   newLesion_),
        };
        MeasurementArchive archive(*store_);
        QVERIFY(!archive.save(prior_.seriesUid, priorMeasurements_).empty());
        QVERIFY(!archive.save(current_.seriesUid, currentMeasurements_).empty());
    }

    // Read back by a fresh archive: the exact geometry, and each lesion's tracking UID,
    // role and lymph-node flag; the plain measurement got a tracking UID of its own,
    // kept from then on.
    void readBackWithTrackingUids() {
        MeasurementArchive archive(*store_);
        std::vector<Measurement> prior = archive.load(prior_.seriesUid).measurements;
        test::compareMeasurements(prior, priorMeasurements_, 1e-6, false);
        for (std::size_t i = 0; i < 3; ++i) {
            QVERIFY(prior[i].lesion == priorMeasurements_[i].lesion);
        }
        QCOMPARE(prior[3].lesion.role, LesionRole::None);
        QVERIFY(!prior[3].lesion.trackingUid.empty());
        const std::vector<Measurement> current = archive.load(current_.seriesUid).measurements;
        QCOMPARE(current.size(), currentMeasurements_.size());
        for (std::size_t i = 0; i < current.size(); ++i) {
            QVERIFY(current[i].lesion == currentMeasurements_[i].lesion);
        }
        QCOMPARE(current[0].lesion.trackingUid, prior[0].lesion.trackingUid); // one lesion

        const std::string plainUid = prior[3].lesion.trackingUid;
        archive.save(prior_.seriesUid, prior);
        QCOMPARE(
            MeasurementArchive(*store_).load(prior_.seriesUid).measurements[3].lesion.trackingUid,
            plainUid);
    }

    // Another program's SR: its tracking UID, Target and the SRT lymph node read too.
    void foreignReportLesion() {
        const fs::path file = fs::path(dir_.path().toStdString()) / "foreign.dcm";
        const std::string uid = newDicomUid();
        QVERIFY(writeForeignLesion(file, current_, current_.images[70], uid));
        const ReadReport read = readMeasurementReport(file, &current_);
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

        const auto& p = priorMeasurements_;
        const auto& c = currentMeasurements_;
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
        QCOMPARE(liver.trackingUid, liver_);
        QCOMPARE(liver.at[0]->where.seriesUid, prior_.seriesUid);
        QCOMPARE(liver.at[1]->where.seriesUid, current_.seriesUid);
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
        test::CliRun run = test::runCli(
            {"measurements", "--patient", kPatient, "--store", storeDir(), "--recist"});
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

        run = test::runCli(
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
        QCOMPARE(liver["tracking_uid"].toString(), QString::fromStdString(liver_));
        QCOMPARE(liver["timepoints"].toArray()[1].toObject()["series_uid"].toString(),
                 QString::fromStdString(current_.seriesUid));
        QVERIFY(json["lesions"].toArray()[3].toObject()["new_lesion"].toBool());

        QCOMPARE(test::runCli({"measurements", "--recist", "--store", storeDir()}).exitCode, 2);
        run = test::runCli(
            {"measurements", "--patient", "NOBODY", "--store", storeDir(), "--recist"});
        QCOMPARE(run.exitCode, 3);
        QVERIFY2(run.err.contains("NOBODY"), qPrintable(run.err));
    }

    void cleanupTestCase() { store_.reset(); }
};

QTEST_GUILESS_MAIN(TestFollowUpStore)
#include "test_followup_store.moc"
