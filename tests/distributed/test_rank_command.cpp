// What a distributed server's rank 0 sends the other ranks: a render command
// comes back whole, a malformed one is refused naming the field, and the root
// the ranks scan holds every file of the series and no more than it must.
#include <QTest>

#include "core/scene/RenderDescriptionJson.h"
#include "render/distributed/RankCommand.h"

using namespace lucent;

namespace {

SeriesEntry dicomEntry(std::initializer_list<const char*> files) {
    SeriesEntry e;
    e.id = "1.2.3";
    e.geometry.dims = {4, 4, int(files.size())};
    for (const char* f : files) {
        e.slices.push_back(SliceRef{f});
    }
    return e;
}

} // namespace

class TestRankCommand : public QObject {
    Q_OBJECT

private slots:
    void renderCommandComesBackWhole() {
        RenderDescription d;
        d.transferFunction = loadPreset("ct-bone");
        d.camera.azimuth = 12.345678901234567;
        d.sampling.interpolation = Interpolation::Cubic;
        d.width = 77;
        const SeriesEntry entry = dicomEntry({"/data/a/1.dcm", "/data/a/2.dcm", "/data/a/3.dcm"});
        const RankCommand sent = renderCommand(42, entry, d);
        const RankCommand got = decodeRankCommand(encodeRankCommand(sent));
        QCOMPARE(got.kind, RankCommand::Kind::Render);
        QCOMPARE(got.series, std::uint64_t(42));
        QCOMPARE(got.seriesId, std::string("1.2.3"));
        QCOMPARE(got.seriesRoot, std::string("/data/a"));
        QCOMPARE(got.slices, std::uint64_t(3));
        QVERIFY(got.dims == glm::ivec3(4, 4, 3));
        QCOMPARE(toJson(got.description), toJson(d));
        QCOMPARE(decodeRankCommand(encodeRankCommand(RankCommand{})).kind, RankCommand::Kind::Stop);
    }

    void malformedCommandsAreRefused() {
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, decodeRankCommand("{\"kind\":\"dance\"}"));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, decodeRankCommand("{\"kind\":\"render\"}"));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, decodeRankCommand("not json"));
    }

    void theRootHoldsEveryFile() {
        QCOMPARE(seriesRoot(dicomEntry({"/s/x/1.dcm", "/s/x/2.dcm"})), std::string("/s/x"));
        QCOMPARE(seriesRoot(dicomEntry({"/s/x/a/1.dcm", "/s/x/b/2.dcm", "/s/x/a/3.dcm"})),
                 std::string("/s/x"));
        QCOMPARE(seriesRoot(dicomEntry({"/s/xy/1.dcm", "/s/x/2.dcm"})), std::string("/s"));
        SeriesEntry file;
        file.file = "/v/ct.mhd";
        QCOMPARE(seriesRoot(file), std::string("/v/ct.mhd"));
    }
};

QTEST_GUILESS_MAIN(TestRankCommand)
#include "test_rank_command.moc"
