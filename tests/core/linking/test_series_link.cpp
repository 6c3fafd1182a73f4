// Linked viewports: where a position of one series lies in another, on real CT.
#include <QTemporaryDir>
#include <QTest>

#include <cmath>
#include <cstring>

#include "core/io/Catalog.h"
#include "core/linking/SeriesLink.h"
#include "core/mpr/PlaneSampler.h"
#include "core/registration/Registration.h"
#include "core/store/StudyStore.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

const char* kCt = "dcm_qa_ct/Philips_S21570/S2020";      // 140 x 1 mm
const char* kCtThick = "dcm_qa_ct/Philips_S21570/S2010"; // the same phantom, 28 x 5 mm

// A copy of `volume` that a different scanner (another Frame of Reference) placed
// `shift` mm away: the same anatomy lies at point + shift.
Volume shiftedCopy(const Volume& volume, const glm::dvec3& shift) {
    VolumeGeometry g = volume.geometry();
    g.origin += shift;
    Volume copy(g, volume.type());
    std::memcpy(copy.bytes().data(), volume.bytes().data(), volume.byteCount());
    static_cast<SeriesInfo&>(copy) = volume;
    copy.seriesUid = volume.seriesUid + ".77";
    copy.frameOfReferenceUid = "1.2.826.0.1.3680043.9.7777.1";
    copy.studyDate = "20200101";
    return copy;
}

// Equal pixels (NaN outside the volume in both), up to float rounding.
bool sameImage(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) {
        return false;
    }
    for (std::size_t n = 0; n < a.size(); ++n) {
        if (std::isnan(a[n]) != std::isnan(b[n]) ||
            (!std::isnan(a[n]) && std::abs(a[n] - b[n]) > 1e-2f)) {
            return false;
        }
    }
    return true;
}

} // namespace

class TestSeriesLink : public QObject {
    Q_OBJECT

private slots:
    void sameFrameOfReferenceLinksByPositionWithoutSetup() {
        REQUIRE_DATA(kCt);
        const Volume thin = loadPath(test::kRealData / kCt);
        const Volume thick = loadPath(test::kRealData / kCtThick);
        QVERIFY(!thin.frameOfReferenceUid.empty());
        QCOMPARE(thick.frameOfReferenceUid, thin.frameOfReferenceUid);
        const SeriesLink link = linkSeries(thin, thick, std::nullopt);
        QVERIFY(link.kind == SeriesLink::Kind::SamePosition);
        const glm::dvec3 axial(0.0, 0.0, 1.0);
        const double half = thick.geometry().spacing.z / 2.0 + 1e-6;
        for (int k = 0; k < thin.dims().z; ++k) {
            const glm::dvec3 p = thin.geometry().toPatient({256.0, 256.0, k});
            const glm::dvec3 landed = linkedPoint(link, thick.geometry(), p, axial);
            // On an acquired slice of the thick series, the nearest one to p.
            const glm::dvec3 ijk = thick.geometry().toIndex(landed);
            QVERIFY(std::abs(ijk.z - std::round(ijk.z)) < 1e-6);
            const bool inside =
                p.z >= thick.geometry().toPatient({0, 0, 0}).z - half &&
                p.z <= thick.geometry().toPatient({0, 0, thick.dims().z - 1}).z + half;
            if (inside) {
                QVERIFY2(std::abs(landed.z - p.z) <= half,
                         qPrintable(QString("slice %1: %2 vs %3").arg(k).arg(landed.z).arg(p.z)));
            }
            // The in-plane position is kept.
            QCOMPARE(landed.x, p.x);
            QCOMPARE(landed.y, p.y);
        }
    }

    void linkHereOffsetLandsWithinHalfASlice() {
        REQUIRE_DATA(kCt);
        const Volume current = loadPath(test::kRealData / kCt);
        const glm::dvec3 shift(12.3, -7.9, 23.45); // not a whole number of slices
        const Volume prior = shiftedCopy(current, shift);
        QVERIFY(linkSeries(current, prior, std::nullopt).kind == SeriesLink::Kind::None);
        QVERIFY(!linkSeries(current, prior, std::nullopt).reason.empty());

        // The reader clicks the same anatomy (a voxel near the phantom's centre) in both;
        // the offset is kept in the store and read back, in either order.
        const glm::dvec3 voxel(301.0, 188.0, 70.0);
        const glm::dvec3 offset =
            linkHereOffset(current.geometry().toPatient(voxel), prior.geometry().toPatient(voxel));
        QTemporaryDir dir;
        {
            StudyStore store(dir.path().toStdString());
            store.setSeriesOffset(current.seriesUid, prior.seriesUid, offset);
        }
        StudyStore store(dir.path().toStdString());
        const auto kept = store.seriesOffset(current.seriesUid, prior.seriesUid);
        QVERIFY(kept.has_value());
        QVERIFY(glm::length(*kept - shift) < 1e-9);
        QVERIFY(glm::length(*store.seriesOffset(prior.seriesUid, current.seriesUid) + shift) <
                1e-9);
        QVERIFY(!store.seriesOffset(current.seriesUid, "1.2.3").has_value());

        const SeriesLink link = linkSeries(current, prior, kept);
        QVERIFY(link.kind == SeriesLink::Kind::Offset);
        const glm::dvec3 axial(0.0, 0.0, 1.0);
        const double half = prior.geometry().spacing.z / 2.0 + 1e-6;
        for (int k = 0; k < current.dims().z; ++k) {
            const glm::dvec3 p = current.geometry().toPatient({200.0, 300.0, k});
            const glm::dvec3 truth = p + shift;
            const glm::dvec3 landed = linkedPoint(link, prior.geometry(), p, axial);
            QVERIFY2(
                std::abs(landed.z - truth.z) <= half,
                qPrintable(
                    QString("slice %1 lands at %2, truth %3").arg(k).arg(landed.z).arg(truth.z)));
            // And the prior's image there is the current one's: the same anatomy.
            if (k % 35 == 0) {
                const SlicePlane a =
                    standardPlane(current.geometry(), Orientation::Axial, p, 64, 64);
                const SlicePlane b =
                    standardPlane(prior.geometry(), Orientation::Axial, landed, 64, 64);
                QVERIFY(sameImage(sampleImage(prior, b), sampleImage(current, a)));
            }
        }
        // Back from the prior to the current series through the reversed link.
        const glm::dvec3 back = linkedPoint(link.reversed(), current.geometry(),
                                            prior.geometry().toPatient({10.0, 20.0, 30.0}), axial);
        QVERIFY(std::abs(back.z - current.geometry().toPatient({10.0, 20.0, 30.0}).z) < 1e-6);
    }

    // "Register" instead of "link here": the transform found by registration links the
    // pair (before any offset), is kept in the store (inverse in the other order), and
    // every slice lands within half a slice of the truth.
    void registrationLinksThroughItsTransform() {
        REQUIRE_DATA(kCtThick);
        const Volume current = loadPath(test::kRealData / kCtThick);
        const glm::dvec3 shift(12.3, -7.9, 11.45);
        const Volume prior = shiftedCopy(current, shift);
        const RegistrationResult r = registerRigid(current, prior, {});
        QTemporaryDir dir;
        {
            StudyStore store(dir.path().toStdString());
            store.setSeriesTransform(current.seriesUid, prior.seriesUid, r.fixedToMoving);
        }
        const StudyStore store(dir.path().toStdString());
        const auto kept = store.seriesTransform(current.seriesUid, prior.seriesUid);
        QVERIFY(kept.has_value());
        const auto back = store.seriesTransform(prior.seriesUid, current.seriesUid);
        QVERIFY(back.has_value());
        QVERIFY(!store.seriesTransform(current.seriesUid, "1.2.3").has_value());

        const SeriesLink link = linkSeries(current, prior, glm::dvec3(100.0), kept);
        QVERIFY(link.kind == SeriesLink::Kind::Registered); // before a stale offset
        const glm::dvec3 axial(0.0, 0.0, 1.0);
        QVERIFY(planesParallel(link.mapDirection(axial), axial));
        const double half = prior.geometry().spacing.z / 2.0 + 1e-6;
        for (int k = 2; k < current.dims().z - 2; ++k) {
            const glm::dvec3 p = current.geometry().toPatient({250.0, 260.0, k});
            const glm::dvec3 landed = linkedPoint(link, prior.geometry(), p, axial);
            QVERIFY2(std::abs(landed.z - (p.z + shift.z)) <= half,
                     qPrintable(QString("slice %1 lands at %2, truth %3")
                                    .arg(k)
                                    .arg(landed.z)
                                    .arg(p.z + shift.z)));
            QVERIFY(std::abs(landed.x - (p.x + shift.x)) < 0.5);
            QVERIFY(std::abs(landed.y - (p.y + shift.y)) < 0.5);
        }
        const glm::dvec3 p = current.geometry().toPatient({250.0, 260.0, 14.0});
        QVERIFY(glm::length(glm::dvec3(*back * glm::dvec4(link.map(p), 1.0)) - p) < 1e-6);
    }

    void aRotatedRegistrationMapsPointsAndPlanes() {
        // 30 degrees about z and a shift: an axial plane stays axial, a coronal one turns.
        const double r = 30.0 * 3.14159265358979323846 / 180.0;
        glm::dmat4 m(1.0);
        m[0] = {std::cos(r), std::sin(r), 0.0, 0.0};
        m[1] = {-std::sin(r), std::cos(r), 0.0, 0.0};
        m[3] = {5.0, -3.0, 2.0, 1.0};
        const SeriesLink link =
            linkSeries(SeriesInfo{"a", "", "CT", "", "", "", "", "f1"},
                       SeriesInfo{"b", "", "CT", "", "", "", "", "f2"}, std::nullopt, m);
        QVERIFY(link.kind == SeriesLink::Kind::Registered);
        const glm::dvec3 moved = link.map({10.0, 0.0, 0.0});
        QVERIFY(glm::length(moved - glm::dvec3(10.0 * std::cos(r) + 5.0, 10.0 * std::sin(r) - 3.0,
                                               2.0)) < 1e-9);
        QVERIFY(glm::length(link.reversed().map(moved) - glm::dvec3(10.0, 0.0, 0.0)) < 1e-9);
        QVERIFY(planesParallel(link.mapDirection({0.0, 0.0, 1.0}), {0.0, 0.0, 1.0}));
        QVERIFY(std::abs(planeAngleDegrees(link.mapDirection({0.0, 1.0, 0.0}), {0.0, 1.0, 0.0}) -
                         30.0) < 1e-9);
    }

    void aNudgeWinsOverASharedFrameOfReference() {
        // A PET and its CT share a Frame of Reference; breathing put them 4 mm apart and the
        // reader nudged the PET: the kept transform is used, not the shared frame.
        const SeriesInfo ct{"ct", "", "CT", "", "", "", "", "f1"};
        const SeriesInfo pet{"pet", "", "PT", "", "", "", "", "f1"};
        QVERIFY(linkSeries(ct, pet, std::nullopt).kind == SeriesLink::Kind::SamePosition);
        glm::dmat4 nudge(1.0);
        nudge[3] = {0.0, 0.0, 4.0, 1.0};
        const SeriesLink link = linkSeries(ct, pet, std::nullopt, nudge);
        QVERIFY(link.kind == SeriesLink::Kind::Registered);
        QVERIFY(glm::length(link.map({1.0, 2.0, 3.0}) - glm::dvec3(1.0, 2.0, 7.0)) < 1e-12);
        // The same series is always itself.
        QVERIFY(linkSeries(ct, ct, std::nullopt, nudge).kind == SeriesLink::Kind::SamePosition);
    }

    void nonParallelPlanesDoNotLink() {
        const glm::dvec3 axial(0.0, 0.0, 1.0);
        const auto tilted = [&](double degrees) {
            const double r = degrees * 3.14159265358979323846 / 180.0;
            return glm::dvec3(0.0, std::sin(r), std::cos(r));
        };
        QVERIFY(planesParallel(axial, -axial)); // the sense does not matter
        QVERIFY(planesParallel(axial, tilted(kParallelToleranceDegrees - 0.1)));
        QVERIFY(!planesParallel(axial, tilted(kParallelToleranceDegrees + 0.1)));
        QVERIFY(!planesParallel(axial, glm::dvec3(0.0, 1.0, 0.0))); // axial vs coronal
        QVERIFY(std::abs(planeAngleDegrees(axial, tilted(18.5)) - 18.5) < 1e-9);
    }

    void offsetNeedsTwoSeries() {
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        QVERIFY_THROWS_EXCEPTION(StoreError, store.setSeriesOffset("1.2", "1.2", {1, 2, 3}));
        QVERIFY_THROWS_EXCEPTION(StoreError, store.setSeriesOffset("", "1.2", {1, 2, 3}));
    }
};

QTEST_GUILESS_MAIN(TestSeriesLink)
#include "test_series_link.moc"
