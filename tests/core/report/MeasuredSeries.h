#pragma once
// Real CT (the 28-slice Philips phantom series) measured with every kind of
// measurement, on one of its acquired axial slices and on an oblique plane,
// and the checks that two sets of measurements are equal (1e-6 in mm, HU, degrees).

#include <QTest>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/Catalog.h"
#include "core/measure/Measurement.h"
#include "core/mpr/RoiStatistics.h"
#include "core/report/ReferencedSeries.h"
#include "tests/support/RealData.h"

namespace lucent::test {

inline const std::filesystem::path kMeasuredSeriesDir =
    kRealData / "dcm_qa_ct/Philips_S21570/S2010";

inline std::vector<std::filesystem::path> seriesFiles() {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(kMeasuredSeriesDir)) {
        if (e.is_regular_file() && e.path().filename() != "LICENSE") {
            files.push_back(e.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

// Six measurements on `plane` (one of each kind), from pixel positions around its centre.
inline std::vector<Measurement> everyKind(const Volume& volume, const SlicePlane& plane,
                                          const std::string& prefix) {
    const auto at = [&](double x, double y) { return plane.pointAt(x, y); };
    const double cx = 0.5 * plane.width, cy = 0.5 * plane.height;
    std::vector<Measurement> out;
    const auto add = [&](MeasurementKind kind, std::vector<glm::dvec3> points, std::string label) {
        Measurement m;
        m.id = out.size() + 1;
        m.kind = kind;
        m.points = std::move(points);
        m.plane = plane;
        m.label = std::move(label);
        out.push_back(std::move(m));
    };
    add(MeasurementKind::Distance, {at(cx - 40.3, cy + 7.1), at(cx + 52.9, cy - 12.7)},
        prefix + " distance");
    out.back().lesion = {LesionRole::NonTarget, false, "2.25.1" + std::to_string(prefix.size())};
    add(MeasurementKind::Angle, {at(cx + 30.2, cy + 1.3), at(cx, cy), at(cx + 11.7, cy - 29.9)},
        "");
    add(MeasurementKind::CobbAngle,
        {at(cx - 50, cy - 20), at(cx - 10, cy - 24.5), at(cx - 48, cy + 30),
         at(cx - 5, cy + 41.25)},
        prefix + " Cobb");
    add(MeasurementKind::Arrow, {at(cx + 60, cy + 60), at(cx + 20.5, cy + 33.3)}, "");
    out.back().text = prefix + ": calcification? (ä)";
    add(MeasurementKind::Bidirectional,
        {at(cx - 20, cy + 50), at(cx + 24, cy + 58), at(cx + 0.5, cy + 44), at(cx + 1.9, cy + 65)},
        prefix + " lesion 1");
    out.back().lesion = {LesionRole::Target, true, "2.25.2" + std::to_string(prefix.size())};
    EllipseRoi roi{at(cx - 3.3, cy - 40.7), 17.25, 9.5};
    Measurement e = makeEllipseMeasurement(plane, roi);
    e.id = out.size() + 1;
    e.label = prefix + " ROI";
    e.statistics = ellipseStatistics(volume, plane, roi);
    e.unit = "HU";
    out.push_back(e);
    return out;
}

// An acquired axial slice of the series: its image's own plane.
inline SlicePlane acquiredPlane(const ReferencedSeries& series, int index) {
    return series.images.at(static_cast<std::size_t>(index)).plane();
}

// A plane tilted about two axes through the volume's centre.
inline SlicePlane obliquePlane(const Volume& volume) {
    const VolumeGeometry& g = volume.geometry();
    SlicePlane plane;
    plane.centre = g.toPatient(0.5 * (glm::dvec3(g.dims) - 1.0));
    plane.u = glm::normalize(glm::dvec3(1.0, 0.2, 0.35));
    plane.v = glm::normalize(glm::cross(glm::normalize(glm::dvec3(0.1, -0.4, 1.0)), plane.u));
    plane.pixelSize = 0.7;
    plane.width = 400;
    plane.height = 300;
    return plane;
}

// Every kind on the acquired slice `slice` (ids 1..6) and on the oblique plane (ids 101..106).
inline std::vector<Measurement> onBothPlanes(const Volume& volume, const ReferencedSeries& series,
                                             int slice) {
    std::vector<Measurement> out = everyKind(volume, acquiredPlane(series, slice), "axial");
    for (Measurement m : everyKind(volume, obliquePlane(volume), "oblique")) {
        m.id += 100;
        out.push_back(m);
    }
    return out;
}

inline bool near(double a, double b, double tolerance = 1e-6) {
    return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= tolerance;
}

// Equal within `tolerance` (mm for points and lengths, degrees, HU), by position.
inline void compareMeasurements(const std::vector<Measurement>& read,
                                const std::vector<Measurement>& written, double tolerance = 1e-6,
                                bool sameIdsAndPlanes = true) {
    QCOMPARE(read.size(), written.size());
    for (std::size_t i = 0; i < read.size(); ++i) {
        const Measurement& r = read[i];
        const Measurement& w = written[i];
        const QByteArray what = QByteArray(measurementKindName(w.kind)) + " " + w.label.c_str();
        QVERIFY2(r.kind == w.kind, what);
        QCOMPARE(r.label, w.label);
        QCOMPARE(r.text, w.text);
        QCOMPARE(r.points.size(), w.points.size());
        // RECIST role, lymph node and tracking UID (a new one where none was given).
        QVERIFY2(r.lesion.role == w.lesion.role && r.lesion.lymphNode == w.lesion.lymphNode, what);
        QVERIFY2(w.lesion.trackingUid.empty() ? !r.lesion.trackingUid.empty()
                                              : r.lesion.trackingUid == w.lesion.trackingUid,
                 what);
        for (std::size_t p = 0; p < r.points.size(); ++p) {
            QVERIFY2(glm::distance(r.points[p], w.points[p]) <= tolerance,
                     what + " point " +
                         QByteArray::number(glm::distance(r.points[p], w.points[p])));
        }
        QVERIFY2(near(measurementLengthMm(r), measurementLengthMm(w), tolerance), what);
        QVERIFY2(near(measurementAngleDegrees(r), measurementAngleDegrees(w), tolerance), what);
        QVERIFY2(near(bidirectionalShortAxisMm(r), bidirectionalShortAxisMm(w), tolerance), what);
        if (w.kind == MeasurementKind::Ellipse) {
            const RoiStatistics &a = r.statistics, &b = w.statistics;
            QVERIFY2(near(a.mean, b.mean, tolerance) &&
                         near(a.standardDeviation, b.standardDeviation, tolerance) &&
                         near(a.minimum, b.minimum, tolerance) &&
                         near(a.maximum, b.maximum, tolerance) &&
                         near(a.areaMm2, b.areaMm2, tolerance),
                     what);
            QCOMPARE(r.unit, w.unit);
            // SUVmax, SUVmean and SUVpeak (a PET series in SUVbw), the voxels only where
            // Lucent's own geometry item keeps them.
            QVERIFY2(r.suv.has_value() == w.suv.has_value(), what + " SUVs");
            if (w.suv) {
                QVERIFY2(near(r.suv->max, w.suv->max, tolerance) &&
                             near(r.suv->mean, w.suv->mean, tolerance) &&
                             near(r.suv->peak, w.suv->peak, tolerance),
                         what + " SUVs");
                QVERIFY2(!sameIdsAndPlanes || r.suv->voxels == w.suv->voxels, what + " voxels");
            }
        }
        if (sameIdsAndPlanes) {
            QCOMPARE(r.id, w.id);
            QVERIFY(!r.readOnly);
            QVERIFY(glm::distance(r.plane.centre, w.plane.centre) < 1e-9);
            QVERIFY(glm::distance(r.plane.u, w.plane.u) < 1e-12);
            QVERIFY(glm::distance(r.plane.v, w.plane.v) < 1e-12);
            QCOMPARE(r.plane.width, w.plane.width);
        }
    }
}

} // namespace lucent::test
