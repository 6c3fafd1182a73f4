#pragma once
// Two real CT studies of one patient ("PLASTIC") in a real study store, measured: the
// Philips phantom's 5 mm series made a prior study (new study, series and instance UIDs,
// 2014-02-06, by DCMTK's dcmodify on copies) and its 1 mm series (2015-02-06) as the
// follow-up. Both saved as Lucent's SRs: at baseline a target lesion "Liver 1"
// (Bidirectional), a target lymph node "Node 1", a non-target "Bone 1" and a plain
// distance; at follow-up "Liver 1" again (a Distance), "Node 1", "Bone 1" (an Arrow), a new
// non-target "New 1" and a plain distance.

#include <QProcess>
#include <QTest>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include "core/report/MeasurementArchive.h"
#include "core/report/MeasurementReport.h"
#include "tests/core/report/MeasuredSeries.h"

namespace lucent::test {

inline const std::filesystem::path kFollowUpDir =
    test::kRealData / "dcm_qa_ct/Philips_S21570/S2020";
inline const char* kPatient = "PLASTIC"; // the phantom's Patient ID

inline std::vector<std::filesystem::path> filesIn(const std::filesystem::path& folder) {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(folder)) {
        if (e.is_regular_file() && e.path().filename() != "LICENSE") {
            files.push_back(e.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

inline std::string tag(DcmItem& d, const DcmTagKey& key) {
    OFString v;
    d.findAndGetOFString(key, v);
    return v.c_str();
}

// Stores a file as a retrieval would, with the index facts read from its header.
inline bool store(StudyStore& store, const std::filesystem::path& file) {
    DcmFileFormat f;
    if (f.loadFile(file.c_str(), EXS_Unknown, EGL_noChange, 4096).bad()) {
        return false;
    }
    DcmDataset& d = *f.getDataset();
    InstanceRecord r;
    r.series = {tag(d, DCM_SeriesInstanceUID), tag(d, DCM_StudyInstanceUID),
                tag(d, DCM_Modality),          tag(d, DCM_SeriesDescription),
                tag(d, DCM_PatientName),       tag(d, DCM_PatientID),
                tag(d, DCM_StudyDate),         tag(d, DCM_FrameOfReferenceUID)};
    r.sopInstanceUid = tag(d, DCM_SOPInstanceUID);
    const std::filesystem::path temp = store.temporaryFile();
    std::filesystem::copy_file(file, temp);
    return store.add(temp, r);
}

inline Measurement lesion(MeasurementKind kind, const SlicePlane& plane,
                          std::vector<glm::dvec2> pixels, const std::string& label, LesionRole role,
                          bool node, const std::string& uid) {
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

inline glm::dvec3 centreOf(const Measurement& m) {
    glm::dvec3 c(0.0);
    for (const glm::dvec3& p : m.points) {
        c += p / static_cast<double>(m.points.size());
    }
    return c;
}

struct TwoStudies {
    ReferencedSeries prior, current;
    std::vector<Measurement> priorMeasurements, currentMeasurements;
    std::string liver = newDicomUid(), node = newDicomUid(), bone = newDicomUid(),
                newLesion = newDicomUid();
};

// Fills `store` (under `dir`) and `out`; the caller checks QTest::currentTestFailed().
inline void makeTwoStudies(const std::filesystem::path& dir, StudyStore& target, TwoStudies& out) {
    namespace fs = std::filesystem;
    // The prior: the 5 mm series as another study a year earlier.
    const fs::path priorDir = dir / "prior";
    fs::create_directories(priorDir);
    QStringList args{"-nb", "-gin",
                     "-m",  "StudyDate=20140206",
                     "-m",  QString("StudyInstanceUID=%1").arg(newDicomUid().c_str()),
                     "-m",  QString("SeriesInstanceUID=%1").arg(newDicomUid().c_str())};
    for (const fs::path& file : seriesFiles()) {
        const fs::path copy = priorDir / file.filename();
        fs::copy_file(file, copy);
        fs::permissions(copy, fs::perms::owner_write, fs::perm_options::add);
        args << QString::fromStdString(copy.string());
    }
    QProcess modify;
    modify.start("dcmodify", args);
    QVERIFY2(modify.waitForFinished(60000) && modify.exitCode() == 0,
             modify.readAllStandardError().constData());
    for (const fs::path& file : filesIn(priorDir)) {
        QVERIFY(store(target, file));
    }
    for (const fs::path& file : filesIn(kFollowUpDir)) {
        QVERIFY(store(target, file));
    }
    out.prior = readReferencedSeries(filesIn(priorDir));
    out.current = readReferencedSeries(filesIn(kFollowUpDir));
    QVERIFY(out.prior.studyUid != out.current.studyUid);

    const SlicePlane before = acquiredPlane(out.prior, 14);
    using K = MeasurementKind;
    using R = LesionRole;
    out.priorMeasurements = {
        lesion(K::Bidirectional, before, {{200, 300}, {251.5, 310}, {224, 290}, {226, 322.25}},
               "Liver 1", R::Target, false, out.liver),
        lesion(K::Bidirectional, before, {{300, 200}, {340, 204}, {318, 190}, {319, 219.5}},
               "Node 1", R::Target, true, out.node),
        lesion(K::Distance, before, {{100, 100}, {130, 110}}, "Bone 1", R::NonTarget, false,
               out.bone),
        lesion(K::Distance, before, {{50, 50}, {90, 60}}, "plain", R::None, false, ""),
    };
    const SlicePlane after = acquiredPlane(out.current, 70);
    out.currentMeasurements = {
        lesion(K::Distance, after, {{200, 300}, {258.25, 312}}, "Liver 1", R::Target, false,
               out.liver),
        lesion(K::Bidirectional, after, {{300, 200}, {345, 205}, {318, 188}, {320, 224.75}},
               "Node 1", R::Target, true, out.node),
        lesion(K::Arrow, after, {{140, 140}, {120, 110}}, "Bone 1", R::NonTarget, false, out.bone),
        lesion(K::Distance, after, {{400, 380}, {420, 392}}, "New 1", R::NonTarget, false,
               out.newLesion),
        lesion(K::Distance, after, {{60, 420}, {95, 431}}, "", R::None, false, ""),
    };
    MeasurementArchive archive(target);
    QVERIFY(!archive.save(out.prior.seriesUid, out.priorMeasurements).empty());
    QVERIFY(!archive.save(out.current.seriesUid, out.currentMeasurements).empty());
}

} // namespace lucent::test
