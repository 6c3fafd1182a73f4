// RECIST 1.1 over timepoints (core/followup/Recist.h) against sums, percentages and
// responses computed by hand in each case, and the table's text (CSV, terminal).
#include <QTest>

#include "core/followup/FollowUpText.h"
#include "core/followup/Recist.h"

using namespace lucent;

namespace {

LesionObservation lesion(const std::string& uid, LesionRole role, double diameterMm,
                         bool node = false) {
    LesionObservation o;
    o.trackingUid = uid;
    o.name = "Lesion " + uid;
    o.role = role;
    o.lymphNode = node;
    o.diameterMm = diameterMm;
    (node ? o.shortAxisMm : o.longAxisMm) = diameterMm;
    return o;
}

LesionObservation target(const std::string& uid, double mm) {
    return lesion(uid, LesionRole::Target, mm);
}
LesionObservation node(const std::string& uid, double shortAxisMm) {
    return lesion(uid, LesionRole::Target, shortAxisMm, true);
}
LesionObservation nonTarget(const std::string& uid) {
    return lesion(uid, LesionRole::NonTarget, 0.0);
}
LesionObservation gone(const std::string& uid) {
    LesionObservation o = target(uid, 0.0);
    o.gone = true;
    return o;
}

TimepointMeasurements at(const std::string& date, std::vector<LesionObservation> lesions) {
    return {date, {"study-" + date}, std::move(lesions)};
}

bool near(const std::optional<double>& v, double expected) {
    return v && std::abs(*v - expected) < 1e-9;
}

Measurement drawn(MeasurementKind kind, std::vector<glm::dvec3> points, LesionRole role,
                  bool lymphNode) {
    Measurement m;
    m.kind = kind;
    m.points = std::move(points);
    m.lesion = {role, lymphNode, "1.2.3.4"};
    m.label = "Node";
    return m;
}

} // namespace

class TestRecist : public QObject {
    Q_OBJECT

private slots:
    // Baseline 50 + 30 + node 20 = 100 mm. Follow-ups, in by-hand sums:
    // 35 + 21 + 14 = 70: -30.0 % exactly -> PR; 30 + 20 + 10 = 60: -40 % -> PR (nadir 70);
    // 40 + 22 + 10 = 72: +12 mm = +20.0 % exactly over the nadir 60 -> PD (and -28 % from
    // baseline, which alone would be SD).
    void partialResponseThenProgressionOverNadir() {
        const FollowUpTable t = assessRecist({
            at("20120301", {target("a", 40), target("b", 22), node("n", 10)}),
            at("20100101", {target("a", 50), target("b", 30), node("n", 20)}),
            at("20110601", {target("a", 30), target("b", 20), node("n", 10)}),
            at("20101015", {target("a", 35), target("b", 21), node("n", 14)}),
        });
        QCOMPARE(t.timepoints.size(), std::size_t(4));
        QCOMPARE(t.timepoints[0].studyDate, std::string("20100101")); // sorted by date
        QCOMPARE(t.timepoints[0].response, RecistResponse::Baseline);
        QCOMPARE(t.timepoints[0].sumMm, 100.0);
        QVERIFY(!t.timepoints[0].fromBaselinePercent && !t.timepoints[0].nadirMm);

        const TimepointAssessment& pr = t.timepoints[1];
        QCOMPARE(pr.sumMm, 70.0);
        QVERIFY(near(pr.fromBaselinePercent, -30.0));
        QVERIFY(near(pr.nadirMm, 100.0));
        QVERIFY(near(pr.fromNadirPercent, -30.0));
        QCOMPARE(pr.response, RecistResponse::PR);

        const TimepointAssessment& pr2 = t.timepoints[2];
        QCOMPARE(pr2.sumMm, 60.0);
        QVERIFY(near(pr2.fromBaselinePercent, -40.0));
        QVERIFY(near(pr2.nadirMm, 70.0));
        QVERIFY(near(pr2.fromNadirPercent, (60.0 - 70.0) / 70.0 * 100.0));
        QCOMPARE(pr2.response, RecistResponse::PR);

        const TimepointAssessment& pd = t.timepoints[3];
        QCOMPARE(pd.sumMm, 72.0);
        QVERIFY(near(pd.nadirMm, 60.0));
        QVERIFY(near(pd.fromNadirPercent, 20.0));
        QVERIFY(near(pd.fromBaselinePercent, -28.0));
        QCOMPARE(pd.response, RecistResponse::PD);
        QVERIFY(!pd.reasons.empty());
    }

    // Thresholds met exactly where floating point misses them by an ulp: 43 -> 30.1 is
    // -30 % (PR); 26 -> 31.2 is +20 % and +5.2 mm (PD).
    void exactThresholdsInFloatingPoint() {
        FollowUpTable t = assessRecist({at("20100101", {target("a", 30), target("b", 13)}),
                                        at("20100401", {target("a", 21.1), target("b", 9)})});
        QCOMPARE(t.timepoints[1].response, RecistResponse::PR);
        t = assessRecist({at("20100101", {target("a", 10), target("b", 16)}),
                          at("20100401", {target("a", 12), target("b", 19.2)})});
        QCOMPARE(t.timepoints[1].response, RecistResponse::PD);
    }

    // Just short of -30 %: 70.5 of 100 is -29.5 % -> SD.
    void justShortOfPartialResponseIsStable() {
        const FollowUpTable t =
            assessRecist({at("20100101", {target("a", 60), target("b", 40)}),
                          at("20100401", {target("a", 40.5), target("b", 30)})});
        QVERIFY(near(t.timepoints[1].fromBaselinePercent, -29.5));
        QCOMPARE(t.timepoints[1].response, RecistResponse::SD);
    }

    // Baseline 10 + 10 = 20. 12 + 12 = 24 is +20 % but only +4 mm over the nadir 20: SD.
    // 12.5 + 12.5 = 25 is +25 % and +5 mm over the nadir (still 20): PD.
    void twentyPercentNeedsFiveMillimetres() {
        const FollowUpTable t =
            assessRecist({at("20100101", {target("a", 10), target("b", 10)}),
                          at("20100401", {target("a", 12), target("b", 12)}),
                          at("20100701", {target("a", 12.5), target("b", 12.5)})});
        QVERIFY(near(t.timepoints[1].fromNadirPercent, 20.0));
        QCOMPARE(t.timepoints[1].response, RecistResponse::SD);
        QVERIFY(near(t.timepoints[2].nadirMm, 20.0));
        QVERIFY(near(t.timepoints[2].fromNadirPercent, 25.0));
        QCOMPARE(t.timepoints[2].response, RecistResponse::PD);
    }

    // A lesion first marked at a follow-up is new: PD whatever the sum (29 of 30: -3.3 %),
    // and it is not summed. The next follow-up judges the sum alone again.
    void newLesionIsProgression() {
        const FollowUpTable t = assessRecist(
            {at("20100101", {target("a", 30), nonTarget("x")}),
             at("20100401", {target("a", 29), nonTarget("x"), nonTarget("new"), target("t2", 15)}),
             at("20100701", {target("a", 28), nonTarget("new"), target("t2", 15)})});
        QCOMPARE(t.timepoints[1].sumMm, 29.0);
        QCOMPARE(t.timepoints[1].response, RecistResponse::PD);
        QCOMPARE(t.timepoints[1].reasons.size(), std::size_t(2)); // both new lesions named
        QCOMPARE(t.lesions.size(), std::size_t(4));
        QCOMPARE(t.lesions[0].trackingUid, std::string("a")); // targets first
        QCOMPARE(t.lesions[1].trackingUid, std::string("t2"));
        QCOMPARE(t.lesions[1].firstTimepoint, std::size_t(1));
        QCOMPARE(t.timepoints[2].sumMm, 28.0);
        QCOMPARE(t.timepoints[2].response, RecistResponse::SD);
        // "Same lesion as" at the second follow-up offers all four, at the first only the
        // baseline's two.
        QCOMPARE(lesionsBefore(t, "20100701").size(), std::size_t(4));
        const auto early = lesionsBefore(t, "20100401");
        QCOMPARE(early.size(), std::size_t(2));
        QCOMPARE(early[0]->trackingUid, std::string("a"));
        QCOMPARE(early[1]->trackingUid, std::string("x"));
        QCOMPARE(lesionsBefore(t, "").size(), std::size_t(4));
    }

    // Baseline 25 + node 18 = 43. The lesion gone and the node at 9.5 mm short axis: CR
    // (the sum is 9.5, -77.9 %). The node back at 10.0 mm: not CR; 10 of 43 is -76.7 %: PR,
    // and +0.5 mm over the nadir 9.5 is no PD.
    void completeResponseWithLymphNodeUnderTenMillimetres() {
        const FollowUpTable t = assessRecist({at("20100101", {target("a", 25), node("n", 18)}),
                                              at("20100401", {gone("a"), node("n", 9.5)}),
                                              at("20100701", {gone("a"), node("n", 10.0)})});
        QCOMPARE(t.timepoints[1].sumMm, 9.5);
        QVERIFY(near(t.timepoints[1].fromBaselinePercent, (9.5 - 43.0) / 43.0 * 100.0));
        QCOMPARE(t.timepoints[1].response, RecistResponse::CR);
        QCOMPARE(t.timepoints[2].sumMm, 10.0);
        QVERIFY(near(t.timepoints[2].nadirMm, 9.5));
        QCOMPARE(t.timepoints[2].response, RecistResponse::PR);
    }

    // Targets gone while a non-target lesion is still marked: PR (RECIST's table 4).
    void nonTargetsPersistingMakeCompleteResponsePartial() {
        const FollowUpTable t = assessRecist({at("20100101", {target("a", 20), nonTarget("x")}),
                                              at("20100401", {gone("a"), nonTarget("x")}),
                                              at("20100701", {gone("a")})});
        QCOMPARE(t.timepoints[1].response, RecistResponse::PR);
        QCOMPARE(t.timepoints[2].response, RecistResponse::CR);
    }

    // A target lesion not measured: NE, and its incomplete sum is no nadir. Unless the
    // measured ones alone show PD (70 of nadir 50: +40 %, +20 mm).
    void unmeasuredTargetIsNotEvaluable() {
        const FollowUpTable t = assessRecist({at("20100101", {target("a", 30), target("b", 20)}),
                                              at("20100401", {target("a", 30)}),
                                              at("20100701", {target("a", 30), target("b", 19)}),
                                              at("20101001", {target("a", 70)})});
        QCOMPARE(t.timepoints[1].response, RecistResponse::NE);
        QVERIFY(!t.timepoints[1].evaluable);
        QVERIFY(near(t.timepoints[2].nadirMm, 50.0)); // not the incomplete 30
        QCOMPARE(t.timepoints[2].response, RecistResponse::SD);
        QVERIFY(near(t.timepoints[3].nadirMm, 49.0));
        QCOMPARE(t.timepoints[3].response, RecistResponse::PD);
    }

    void noTargetAtBaselineIsNotEvaluable() {
        const FollowUpTable t =
            assessRecist({at("20100101", {nonTarget("x")}), at("20100401", {nonTarget("x")})});
        QCOMPARE(t.timepoints[1].response, RecistResponse::NE);
    }

    // What each kind measures: a Bidirectional both axes (a node by its short one), a
    // Distance on a node its short axis, an Ellipse its two axes, an Arrow on a target "gone".
    void diameterOfEachKind() {
        const LesionLocation where{"20100101", "study", "series", glm::dvec3(0.0)};
        const std::vector<glm::dvec3> bidi{{0, 0, 0}, {20, 0, 0}, {10, -6, 0}, {10, 6, 0}};
        auto o = lesionObservationOf(
            drawn(MeasurementKind::Bidirectional, bidi, LesionRole::Target, true), where);
        QVERIFY(o);
        QCOMPARE(o->longAxisMm, 20.0);
        QCOMPARE(o->shortAxisMm, 12.0);
        QCOMPARE(o->diameterMm, 12.0);
        QVERIFY(glm::distance(o->where.centre, glm::dvec3(10, 0, 0)) < 1e-12);
        QCOMPARE(o->where.seriesUid, std::string("series"));
        o = lesionObservationOf(
            drawn(MeasurementKind::Bidirectional, bidi, LesionRole::Target, false), where);
        QCOMPARE(o->diameterMm, 20.0);
        o = lesionObservationOf(
            drawn(MeasurementKind::Distance, {{0, 0, 0}, {0, 3, 4}}, LesionRole::Target, true),
            where);
        QCOMPARE(o->shortAxisMm, 5.0);
        QCOMPARE(o->diameterMm, 5.0);
        o = lesionObservationOf(drawn(MeasurementKind::Ellipse,
                                      {{-5, 0, 0}, {5, 0, 0}, {0, -3, 0}, {0, 3, 0}},
                                      LesionRole::Target, false),
                                where);
        QCOMPARE(o->longAxisMm, 10.0);
        QCOMPARE(o->shortAxisMm, 6.0);
        o = lesionObservationOf(
            drawn(MeasurementKind::Arrow, {{0, 0, 0}, {1, 1, 0}}, LesionRole::Target, false),
            where);
        QVERIFY(o->gone);
        QCOMPARE(o->diameterMm, 0.0);
        QVERIFY(
            !lesionObservationOf(drawn(MeasurementKind::Angle, {{1, 0, 0}, {0, 0, 0}, {0, 1, 0}},
                                       LesionRole::Target, false),
                                 where));
        QVERIFY(!lesionObservationOf(
            drawn(MeasurementKind::Distance, {{0, 0, 0}, {1, 0, 0}}, LesionRole::None, false),
            where));
    }

    void csvAndText() {
        LesionObservation quoted = target("a", 12.25);
        quoted.name = "Liver, \"segment 7\"";
        const FollowUpTable t =
            assessRecist({at("20100101", {quoted, nonTarget("x")}), at("20100401", {gone("a")})});
        const std::string csv = followUpCsv(t);
        QCOMPARE(csv, std::string("Lesion,Role,2010-01-01,2010-04-01\r\n"
                                  "\"Liver, \"\"segment 7\"\"\",Target,12.2,0 (gone)\r\n"
                                  "Lesion x,Non-target,present,\r\n"
                                  "Sum of diameters (mm),,12.2,0.0\r\n"
                                  "Change from baseline,,,-100.0 %\r\n"
                                  "Change from nadir,,,-100.0 %\r\n"
                                  "Response,,Baseline,CR\r\n"
                                  "Reason,,,target lesions gone (lymph nodes under 10 mm)\r\n"));
        // Aligned: each column starts where its header does.
        const std::string text = followUpText(t);
        const std::size_t header = text.find("2010-04-01");
        const std::size_t response = text.find("\nResponse ");
        QVERIFY(header != std::string::npos && response != std::string::npos);
        QCOMPARE(text.substr(response + 1 + header, 2), std::string("CR"));
    }
};

QTEST_APPLESS_MAIN(TestRecist)
#include "test_recist.moc"
