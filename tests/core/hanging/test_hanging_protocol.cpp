// Hanging protocols on real series headers of ../shared/data: which protocol wins,
// which series goes where, ties, rules that must match, the study order, the
// shipped defaults, malformed files named in their errors, write -> read.
#include <QTemporaryDir>
#include <QTest>

#include <fstream>

#include "core/hanging/HangingProtocolJson.h"
#include "core/io/Catalog.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

const std::filesystem::path kPhilips = test::kRealData / "dcm_qa_ct/Philips_S21570";
const std::filesystem::path kTilted = test::kRealData / "dcm_qa_ct/Philips_S21610";

std::vector<HangingSeries> scanned(const std::filesystem::path& path) {
    std::vector<HangingSeries> result;
    for (const SeriesEntry& e : scanPath(path).series) {
        result.push_back(hangingSeriesOf(e, path.string()));
    }
    return result;
}

const HangingSeries& byDescription(const std::vector<HangingSeries>& series,
                                   const std::string& description, int studyOrder = 0) {
    for (const HangingSeries& s : series) {
        if (s.description == description && s.studyOrder == studyOrder) {
            return s;
        }
    }
    throw std::runtime_error("no series '" + description + "'");
}

std::vector<HangingProtocol> shipped() {
    std::vector<std::string> errors;
    auto protocols = loadHangingProtocols(shippedHangingFolders(), &errors);
    if (!errors.empty()) {
        throw std::runtime_error(errors.front());
    }
    return protocols;
}

// The series in the viewport of `slot` in the result's set ("" when empty).
std::string seriesIn(const HangingResult& r, const std::string& slot) {
    for (const ViewportAssignment& v : r.viewports) {
        if (v.spec.seriesSlot == slot) {
            return v.series ? v.series->description + "@" + std::to_string(v.series->studyOrder)
                            : "";
        }
    }
    throw std::runtime_error("no viewport of slot " + slot);
}

// A copy of a study's headers as another study of the same patient.
std::vector<HangingSeries> asStudy(std::vector<HangingSeries> series, const std::string& studyUid,
                                   const std::string& date) {
    for (HangingSeries& s : series) {
        s.studyUid = studyUid;
        s.seriesUid += "." + date;
        s.id = s.seriesUid;
        s.studyDate = date;
    }
    return series;
}

// The ranking in words, for failure messages.
std::string describe(const std::vector<HangingResult>& ranking) {
    std::string text;
    for (const HangingResult& r : ranking) {
        text += r.protocol->name + " " + std::to_string(r.score) +
                (r.applicable ? "" : " (" + r.reason + ")") + "; ";
    }
    return text;
}

std::string errorOf(const std::string& text) {
    try {
        parseHangingProtocol(text, "bad.json");
    } catch (const HangingProtocolError& e) {
        return e.what();
    }
    return "no error";
}

const char* kMinimal = R"({"name": "P", "series": [{"name": "a"}],
    "viewportSets": [{"layout": "1x1", "viewports": [{"series": "a"}]}]})";

HangingProtocol protocol(const std::string& name, std::vector<SeriesRule> rules,
                         std::vector<ViewportSpec> viewports) {
    HangingProtocol p;
    p.name = name;
    p.seriesSlots = std::move(rules);
    ViewportSet set;
    set.rows = 1;
    set.columns = static_cast<int>(viewports.size());
    for (std::size_t n = 0; n < viewports.size(); ++n) {
        viewports[n].column = static_cast<int>(n);
    }
    set.viewports = std::move(viewports);
    p.viewportSets = {set};
    return p;
}

ViewportSpec viewportOf(const std::string& slot) {
    ViewportSpec v;
    v.seriesSlot = slot;
    return v;
}

} // namespace

class TestHangingProtocol : public QObject {
    Q_OBJECT

private slots:
    void factsOfRealHeaders() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21610");
        const auto philips = scanned(kPhilips);
        const HangingSeries& thin = byDescription(philips, "STD BRAIN 1MM, iDose");
        QCOMPARE(thin.instances, 140);
        QCOMPARE(thin.sliceThickness, 1.0);
        QCOMPARE(thin.seriesNumber, 202);
        QCOMPARE(thin.bodyPart, std::string("BRAIN"));
        QCOMPARE(thin.studyTime, std::string("092815.672"));
        QCOMPARE(thin.studyDescription, std::string("1A TRAUMA/PLAIN HEAD DM"));
        QVERIFY(thin.orientation == SliceOrientation::Axial);
        const HangingSeries& scout = byDescription(philips, "");
        QVERIFY(scout.kind == SeriesKind::Localizer);
        QVERIFY(scout.orientation == SliceOrientation::Sagittal);
        // A gantry tilt of 18.5 degrees is still axial; 45 degrees is oblique.
        const auto tilted = scanned(kTilted);
        QVERIFY(byDescription(tilted, "STEREOTAXIS").orientation == SliceOrientation::Axial);
        const double h = std::sqrt(0.5);
        QVERIFY(sliceOrientationOf({1, 0, 0}, {0, h, -h}) == SliceOrientation::Oblique);
        QVERIFY(sliceOrientationOf({0, 1, 0}, {0, 0, -1}) == SliceOrientation::Sagittal);
        QVERIFY(sliceOrientationOf({1, 0, 0}, {0, 0, -1}) == SliceOrientation::Coronal);
    }

    void studiesOrderedNewestFirstPerPatient() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21610");
        // Two real studies of the phantom PLASTIC on one day: S21610 (09:34) after S21570.
        auto series = scanned(kPhilips);
        for (HangingSeries& s : scanned(kTilted)) {
            series.push_back(s);
        }
        HangingSeries other = series.front();
        other.studyUid = "1.2.3.other";
        other.patientId = "SOMEONE ELSE";
        other.studyDate = "20990101";
        series.push_back(other);
        // The newest is another patient's: name the current study.
        const std::string tiltedStudy = scanned(kTilted).front().studyUid;
        auto ordered = orderStudies(series, tiltedStudy);
        QCOMPARE(byDescription(ordered, "STEREOTAXIS").studyOrder, 0);
        QCOMPARE(byDescription(ordered, "STD BRAIN 5MM", 1).studyOrder, 1);
        QCOMPARE(ordered.back().studyOrder, -1);
        // With the older study as current, the newer one is no prior.
        ordered = orderStudies(series, scanned(kPhilips).front().studyUid);
        QCOMPARE(byDescription(ordered, "STEREOTAXIS", -1).studyOrder, -1);
        QCOMPARE(byDescription(ordered, "STD BRAIN 5MM").studyOrder, 0);
        // Without a current study the newest of all is current.
        ordered = orderStudies(series);
        QCOMPARE(ordered.back().studyOrder, 0);
        QCOMPARE(byDescription(ordered, "STEREOTAXIS", -1).studyOrder, -1);
    }

    void ctHeadTakesThickForBrainAndThinForBone() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570");
        const auto protocols = shipped();
        const auto series = orderStudies(scanned(kPhilips));
        const auto ranking = rankProtocols(protocols, series);
        QCOMPARE(ranking.front().protocol->name, std::string("CT head: brain and bone"));
        QVERIFY(ranking.front().applicable);
        QCOMPARE(seriesIn(ranking.front(), "brain"), std::string("STD BRAIN 5MM@0"));
        QCOMPARE(seriesIn(ranking.front(), "bone"), std::string("STD BRAIN 1MM, iDose@0"));
        QCOMPARE(ranking.front().viewports[0].spec.windowPreset, std::string("Brain"));
        QCOMPARE(ranking.front().viewports[1].spec.windowPreset, std::string("Bone"));
        // It asks for a prior that is not there: the fetcher's cue.
        QCOMPARE(ranking.front().missingStudyOrders, std::vector<int>{1});
        // No localizer anywhere.
        for (const HangingResult& r : ranking) {
            for (const ViewportAssignment& v : r.viewports) {
                QVERIFY(!v.series || v.series->kind != SeriesKind::Localizer);
            }
        }
        // Before the priors lookup the generic compare (its prior required) still
        // applies; once every prior is there it does not, and MPR 2x2 comes after it.
        const auto name = [](const HangingResult& r) { return r.protocol->name; };
        QCOMPARE(name(ranking[1]), std::string("Current vs prior"));
        QVERIFY(ranking[1].applicable);
        const auto settled = rankProtocols(protocols, series, RankOptions{true});
        QCOMPARE(name(settled[1]), std::string("MPR 2x2"));
        const auto compare = std::find_if(settled.begin(), settled.end(), [&](const auto& r) {
            return name(r) == "Current vs prior";
        });
        QVERIFY(!compare->applicable);
        QVERIFY2(compare->reason.find("'prior'") != std::string::npos, compare->reason.c_str());
    }

    void ctHeadHangsThePriorOfTheSamePatient() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21610");
        auto series = scanned(kPhilips);
        for (HangingSeries& s : scanned(kTilted)) {
            series.push_back(s);
        }
        series = orderStudies(series);
        const auto protocols = shipped();
        const auto ranking = rankProtocols(protocols, series, RankOptions{true});
        QCOMPARE(ranking.front().protocol->name, std::string("CT head: brain and bone"));
        QCOMPARE(seriesIn(ranking.front(), "brain"), std::string("STEREOTAXIS@0"));
        // One current volume: bone falls back to it.
        QCOMPARE(seriesIn(ranking.front(), "bone"), std::string("STEREOTAXIS@0"));
        QVERIFY(ranking.front().missingStudyOrders.empty());
        const HangingResult againstPrior = applyProtocol(*ranking.front().protocol, series, 1);
        QCOMPARE(seriesIn(againstPrior, "prior"), std::string("STD BRAIN 5MM@1"));
        QCOMPARE(againstPrior.viewports[0].spec.linkGroup,
                 againstPrior.viewports[1].spec.linkGroup);
        // Out-of-range sets clamp.
        QCOMPARE(applyProtocol(*ranking.front().protocol, series, 99).viewportSet, 2);
    }

    void ctChestSoftTissueAndLungAgainstPrior() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570");
        auto current = scanned(kPhilips);
        for (HangingSeries& s : current) {
            s.bodyPart = "CHEST";
            s.studyDescription = "CT THORAX"; // the real one names the head
            if (s.description == "STD BRAIN 5MM") {
                s.description = "LUNG 5MM";
            }
        }
        current = asStudy(current, "1.2.3.current", "20250301");
        auto series = current;
        for (const HangingSeries& s : asStudy(current, "1.2.3.prior", "20240301")) {
            series.push_back(s);
        }
        series = orderStudies(series);
        const auto protocols = shipped(); // results point into them
        const auto ranking = rankProtocols(protocols, series, RankOptions{true});
        const HangingResult& best = ranking.front();
        QCOMPARE(best.protocol->name, std::string("CT chest/abdomen: current vs prior"));
        QCOMPARE(seriesIn(best, "current"), std::string("STD BRAIN 1MM, iDose@0"));
        QCOMPARE(seriesIn(best, "prior"), std::string("STD BRAIN 1MM, iDose@1"));
        QCOMPARE(seriesIn(best, "lung"), std::string("LUNG 5MM@0"));
        QCOMPARE(seriesIn(best, "prior lung"), std::string("LUNG 5MM@1"));
        QCOMPARE(best.viewports.size(), std::size_t(4));
        QCOMPARE(best.viewports[2].spec.windowPreset, std::string("Lung"));
        QCOMPARE(best.viewports[1].series->studyDate, std::string("20240301"));
        // Without a lung series the lung viewport shows the soft-tissue one.
        for (HangingSeries& s : series) {
            if (s.description == "LUNG 5MM") {
                s.description = "STD 5MM";
            }
        }
        const HangingResult fallback = rankProtocols(protocols, series).front();
        QCOMPARE(seriesIn(fallback, "lung"), std::string("STD BRAIN 1MM, iDose@0"));
        QVERIFY(fallback.slotAssignments[1].fromFallback);
    }

    void mrBrainFindsSequencesByDescription() {
        REQUIRE_DATA("nema_wg04/MR1");
        const auto mr = scanned(test::kRealData / "nema_wg04/MR1/MR1_UNC.dcm");
        QCOMPARE(mr.size(), std::size_t(1));
        std::vector<HangingSeries> series;
        for (const char* d : {"t1_mprage_tra", "t2_star_gre_tra", "t2_tse_tra",
                              "t2_tirm_tra_dark-fluid", "ep2d_diff_tra_TRACEW"}) {
            HangingSeries s = mr.front();
            s.description = d;
            s.seriesUid += std::string(".") + d;
            s.bodyPart = "BRAIN";
            series.push_back(s);
        }
        series = orderStudies(series);
        const auto protocols = shipped(); // results point into them
        const auto ranking = rankProtocols(protocols, series, RankOptions{true});
        const HangingResult& best = ranking.front();
        QVERIFY2(best.applicable, describe(ranking).c_str());
        QCOMPARE(best.protocol->name, std::string("MR brain: T1, T2, FLAIR, DWI"));
        QCOMPARE(seriesIn(best, "t1"), std::string("t1_mprage_tra@0"));
        QCOMPARE(seriesIn(best, "t2"), std::string("t2_tse_tra@0"));
        QCOMPARE(seriesIn(best, "flair"), std::string("t2_tirm_tra_dark-fluid@0"));
        QCOMPARE(seriesIn(best, "dwi"), std::string("ep2d_diff_tra_TRACEW@0"));
        // A brain MR with none of the four: the protocol would show nothing, so not it.
        for (HangingSeries& s : series) {
            s.description = "localizer";
        }
        const auto none = rankProtocols(protocols, series, RankOptions{true});
        const auto mrBrain = std::find_if(none.begin(), none.end(), [](const auto& r) {
            return r.protocol->name == "MR brain: T1, T2, FLAIR, DWI";
        });
        QVERIFY(!mrBrain->applicable);
    }

    void ruleThatMustMatchExcludes() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570");
        const auto series = orderStudies(scanned(kPhilips));
        SeriesRule flair;
        flair.name = "flair";
        flair.description = "FLAIR";
        flair.scoring.mustMatch[static_cast<int>(Criterion::Description)] = true;
        flair.required = true;
        const HangingProtocol p = protocol("needs FLAIR", {flair}, {viewportOf("flair")});
        const HangingResult r = applyProtocol(p, series);
        QVERIFY(!r.applicable);
        QCOMPARE(r.reason, std::string("no series for the required slot 'flair'"));
        QVERIFY(!scoreSeries(flair, series.front()));
        // Not required to match: the criterion only adds its weight.
        flair.scoring.mustMatch = {};
        flair.scoring.weight[static_cast<int>(Criterion::Description)] = 5;
        QCOMPARE(scoreSeries(flair, series.front()).value_or(-1), 0.0);
        HangingSeries named = series.front();
        named.description = "t2 flair";
        QCOMPARE(scoreSeries(flair, named).value_or(-1), 5.0);
        named.studyOrder = 1; // another study never matches a slot of the current one
        QVERIFY(!scoreSeries(flair, named));
        // The study rule: MR brain on CT names the criterion.
        const auto protocols = shipped();
        const auto ranking = rankProtocols(protocols, series);
        QVERIFY(ranking.back().reason.find("modality") != std::string::npos);
    }

    void tiesGoByFilledViewportsThenName() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570");
        const auto series = orderStudies(scanned(kPhilips));
        SeriesRule any;
        any.name = "a";
        any.kinds = {SeriesKind::Volume};
        SeriesRule mr = any;
        mr.name = "b";
        mr.modalities = {"MR"};
        mr.scoring.mustMatch[static_cast<int>(Criterion::Modality)] = true;
        mr.scoring.weight[static_cast<int>(Criterion::Modality)] = 0;
        mr.scoring.weight[static_cast<int>(Criterion::Kind)] = 0;
        const std::vector<HangingProtocol> protocols{
            protocol("Zeta", {any}, {viewportOf("a")}),
            protocol("Alpha", {any}, {viewportOf("a")}),
            // Same score (the MR slot finds nothing); one of its two viewports stays empty.
            protocol("Aardvark", {any, mr}, {viewportOf("a"), viewportOf("b")}),
            protocol("Two", {any}, {viewportOf("a"), viewportOf("a")}),
        };
        const auto ranking = rankProtocols(protocols, series);
        std::vector<std::string> names;
        for (const HangingResult& r : ranking) {
            names.push_back(r.protocol->name);
            QCOMPARE(r.score, 1.0);
        }
        QCOMPARE(names, (std::vector<std::string>{"Two", "Aardvark", "Alpha", "Zeta"}));
        // Candidates of equal score: more images first (the 140-slice series).
        QCOMPARE(ranking.front().viewports[0].series->instances, 140);
    }

    void shippedDefaultsLoad() {
        std::vector<std::string> errors;
        const auto protocols = loadHangingProtocols(shippedHangingFolders(), &errors);
        QVERIFY2(errors.empty(), errors.empty() ? "" : errors.front().c_str());
        std::vector<std::string> names;
        for (const HangingProtocol& p : protocols) {
            names.push_back(p.name);
            for (const ViewportSet& set : p.viewportSets) {
                for (const ViewportSpec& v : set.viewports) {
                    QVERIFY(p.slot(v.seriesSlot));
                }
            }
        }
        std::sort(names.begin(), names.end());
        QCOMPARE(names, (std::vector<std::string>{"CT chest/abdomen: current vs prior",
                                                  "CT head: brain and bone", "Current vs prior",
                                                  "MPR 2x2", "MR brain: T1, T2, FLAIR, DWI"}));
        // The asymmetric layout: one tall cell on the left, two on the right.
        const HangingProtocol& head =
            *std::find_if(protocols.begin(), protocols.end(),
                          [](const auto& p) { return p.name == "CT head: brain and bone"; });
        const ViewportSet& bone = head.viewportSets[2];
        QCOMPARE(bone.rows, 2);
        QCOMPARE(bone.viewports[0].rowSpan, 2);
        QCOMPARE(bone.viewports[1].column, 1);
        QCOMPARE(bone.viewports[2].row, 1);
    }

    void malformedFilesNamedInErrors() {
        QVERIFY(errorOf(kMinimal) == "no error");
        QVERIFY2(errorOf("{\"name\": ").starts_with("bad.json: not valid JSON"),
                 errorOf("{").c_str());
        const auto has = [](const std::string& text, const std::string& expected) {
            const std::string e = errorOf(text);
            if (e.find(expected) == std::string::npos) {
                qWarning("%s", e.c_str());
                return false;
            }
            return true;
        };
        std::string t = kMinimal;
        const auto with = [&](const std::string& from, const std::string& to) {
            std::string s = t;
            s.replace(s.find(from), from.size(), to);
            return s;
        };
        QVERIFY(has(with("{\"name\": \"a\"}", "{\"name\": \"a\", \"modalty\": \"CT\"}"),
                    "bad.json: series[0].modalty: unknown key; the known keys are name,"));
        QVERIFY(has(with("\"name\": \"P\"", "\"name\": \"P\", \"priority\": \"high\""),
                    "bad.json: priority: expected a number, got string"));
        QVERIFY(has(with("{\"name\": \"a\"}", "{\"name\": \"a\", \"description\": \"T1(\"}"),
                    "bad.json: series[0].description: bad regular expression 'T1('"));
        QVERIFY(has(with("{\"series\": \"a\"}", "{\"series\": \"b\"}"),
                    "bad.json: viewportSets[0].viewports[0].series: 'b' is no slot"));
        QVERIFY(has(with("{\"series\": \"a\"}", "{\"series\": \"a\", \"window\": \"lungs\"}"),
                    "viewports[0].window: unknown window preset 'lungs'; the presets are Brain,"));
        QVERIFY(has(with("{\"series\": \"a\"}", "{\"series\": \"a\", \"view\": \"4d\"}"),
                    "viewports[0].view: '4d' is none of axial, coronal, sagittal, oblique, 3d"));
        QVERIFY(has(with("\"1x1\"", "\"5x1\""), "viewportSets[0].layout: '5x1' is none of"));
        QVERIFY(has(with("{\"series\": \"a\"}", "{\"series\": \"a\"}, {\"series\": \"a\"}"),
                    "viewportSets[0].viewports: 2 viewports do not fit a 1x1 grid"));
        QVERIFY(has(with("{\"name\": \"a\"}",
                         "{\"name\": \"a\", \"sliceThickness\": {\"min\": 5, \"max\": 1}}"),
                    "series[0].sliceThickness: min is above max"));
        QVERIFY(has(with("{\"name\": \"a\"}", "{\"name\": \"a\", \"mustMatch\": [\"colour\"]}"),
                    "series[0].mustMatch: 'colour' is none of modality, bodyPart"));
        QVERIFY(has(with("{\"name\": \"a\"}", "{\"name\": \"a\", \"required\": 1}"),
                    "series[0].required: expected true or false, got number"));
        QVERIFY(has(with("{\"name\": \"a\"}", "{\"name\": \"a\", \"fallback\": \"a\"}"),
                    "series[0].fallback: 'a' is no other slot"));
        t = R"({"name": "P", "series": [{"name": "a"}], "viewportSets": [{"rows": 2,
            "columns": 2, "viewports": [{"series": "a", "row": 0, "column": 0, "rowSpan": 2},
            {"series": "a", "row": 1, "column": 0}]}]})";
        QVERIFY(has(t, "viewportSets[0].viewports[1]: overlaps viewport 0 at row 1, column 0"));
    }

    void loaderListsBadFilesAndLetsTheUserOverride() {
        QTemporaryDir dir;
        const std::filesystem::path user = dir.filePath("user").toStdString();
        std::filesystem::create_directories(user);
        std::ofstream(user / "broken.json") << R"({"name": "X", "series": 3})";
        HangingProtocol mine = shipped().front();
        mine.priority = 7;
        writeHangingProtocol(user / hangingProtocolFileName(mine.name), mine);
        std::vector<std::string> errors;
        const auto loaded = loadHangingProtocols(hangingFolders(user), &errors);
        QCOMPARE(errors.size(), std::size_t(1));
        QCOMPARE(errors.front(), (user / "broken.json").string() +
                                     ": series: expected a non-empty list of series slots");
        QCOMPARE(loaded.size(), shipped().size());
        const auto it = std::find_if(loaded.begin(), loaded.end(),
                                     [&](const auto& p) { return p.name == mine.name; });
        QCOMPARE(it->priority, 7.0);
        QVERIFY(it->file.starts_with(user.string()));
        QCOMPARE(hangingProtocolFileName("CT chest/abdomen: current vs prior"),
                 std::string("ct-chest-abdomen-current-vs-prior.json"));
        QCOMPARE(userHangingFolder("/home/u/.local/share"),
                 std::filesystem::path("/home/u/.local/share/lucent/hanging"));
    }

    void writeThenReadGivesTheSameProtocol() {
        QTemporaryDir dir;
        std::vector<HangingProtocol> protocols = shipped();
        SeriesRule every;
        every.name = "every";
        every.studyOrder = kAnyStudy;
        every.modalities = {"CT", "MR"};
        every.bodyPart = "CHEST";
        every.description = "A|B";
        every.minSliceThickness = 0.625;
        every.maxSliceThickness = 1.25;
        every.orientations = {SliceOrientation::Oblique, SliceOrientation::Coronal};
        every.minInstances = 3;
        every.kinds = {SeriesKind::Image, SeriesKind::Localizer};
        every.scoring.weight[static_cast<int>(Criterion::Instances)] = 0.3;
        every.scoring.mustMatch[static_cast<int>(Criterion::Kind)] = true;
        every.required = true;
        SeriesRule other;
        other.name = "other";
        other.studyOrder = 2;
        other.fallback = "every";
        HangingProtocol p;
        p.name = "Saved layout";
        p.description = "from the View menu";
        p.priority = 2.5;
        p.study.modalities = {"CT"};
        p.study.description = "FOLLOW";
        p.study.scoring.mustMatch[static_cast<int>(Criterion::Modality)] = true;
        p.seriesSlots = {every, other};
        ViewportSet set{"2+1", 2, 2, {}};
        set.viewports = {{0, 0, 1, 1, "every", ViewportView::Stack, "", 0},
                         {1, 0, 1, 1, "other", ViewportView::Oblique, "Liver", 3},
                         {0, 1, 2, 1, "every", ViewportView::Volume3D, "", 0}};
        p.viewportSets = {set};
        protocols.push_back(p);
        for (const HangingProtocol& original : protocols) {
            const std::filesystem::path file =
                dir.filePath(QString::fromStdString(hangingProtocolFileName(original.name)))
                    .toStdString();
            writeHangingProtocol(file, original);
            const HangingProtocol back = readHangingProtocol(file);
            QVERIFY2(back == original, original.name.c_str());
            QCOMPARE(back.file, file.string());
        }
        // What the reader would refuse is not written.
        p.viewportSets[0].viewports[0].windowPreset = "Nonsense";
        QVERIFY_THROWS_EXCEPTION(HangingProtocolError,
                                 writeHangingProtocol(dir.filePath("x.json").toStdString(), p));
        QVERIFY(!std::filesystem::exists(dir.filePath("x.json").toStdString()));
    }
};

QTEST_APPLESS_MAIN(TestHangingProtocol)
#include "test_hanging_protocol.moc"
