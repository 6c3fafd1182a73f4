// The SEG of a series in the study store: saved beside the real CT, replaced by the next save
// (one SEG, same series), found and loaded back equal; a SEG another program stored with the
// study loads too; no segment left removes it. lucent-cli segment -o SEG.dcm and
// segment-stats of that SEG on the CT; an empty result writes nothing (exit 3).
#include <QTemporaryDir>
#include <QTest>

#include "core/segdicom/SegmentationArchive.h"
#include "core/segmentation/SegmentStatistics.h"
#include "tests/core/report/StoredCopies.h"
#include "tests/core/segdicom/SegmentedCt.h"
#include "tests/support/CliRunner.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

std::size_t segsIn(const StudyStore& store) {
    std::size_t n = 0;
    for (const StoredSeries& s : store.listSeries()) {
        n += s.info.modality == "SEG" ? s.stored : 0;
    }
    return n;
}

} // namespace

class TestSegmentationArchive : public QObject {
    Q_OBJECT
    Volume ct_;
    ReferencedSeries series_;

private slots:
    void initTestCase() {
        REQUIRE_DATA(test::kSegmentedCt);
        ct_ = loadPath(test::kRealData / test::kSegmentedCt);
        series_ = readReferencedSeries(test::segmentedCtFiles());
    }

    void savedReplacedFoundAndLoaded() {
        QTemporaryDir here;
        StudyStore store(here.path().toStdString());
        for (const fs::path& file : test::segmentedCtFiles()) {
            QVERIFY(test::storeCopy(store, file, "CT"));
        }
        SegmentationArchive archive(store);
        Segmentation seg = test::segmentedCt(ct_);
        const std::string first = archive.save(series_.seriesUid, seg);
        QVERIFY(!first.empty());
        QCOMPARE(segsIn(store), std::size_t(1));
        const auto found = archive.find(series_.seriesUid);
        QCOMPARE(found.size(), std::size_t(1));
        QCOMPARE(found.front().header.sopInstanceUid, first);
        const std::string segSeries = found.front().header.seriesUid;

        // An edit, saved again: the new SEG replaces the old one in the same series.
        seg.rename(seg.segments().front().id, "Cranium");
        const std::string second = archive.save(series_.seriesUid, seg);
        QVERIFY(second != first);
        QCOMPARE(segsIn(store), std::size_t(1));
        QVERIFY(!store.contains(first));
        QVERIFY(store.contains(second));
        QCOMPARE(archive.find(series_.seriesUid).front().header.seriesUid, segSeries);
        QVERIFY(fs::is_empty(store.root() / "tmp"));

        // Loaded in another session: equal.
        SegmentationArchive later(store);
        const SegmentationArchive::LoadResult loaded =
            later.load(series_.seriesUid, ct_.geometry());
        QVERIFY(loaded.errors.empty());
        QCOMPARE(loaded.loaded.size(), std::size_t(1));
        const auto& read = loaded.loaded.front().segmentation.segments;
        QCOMPARE(read.size(), seg.segments().size());
        QCOMPARE(read.front().name, std::string("Cranium"));
        for (std::size_t i = 0; i < read.size(); ++i) {
            QVERIFY(*read[i].mask == *seg.segments()[i].mask);
        }

        // No segment left: the SEG goes.
        Segmentation none(ct_.geometry());
        QCOMPARE(archive.save(series_.seriesUid, none), std::string());
        QCOMPARE(segsIn(store), std::size_t(0));
        QVERIFY(archive.find(series_.seriesUid).empty());
    }

    void aForeignSegOfTheStudyLoadsToo() {
        REQUIRE_DATA("dcmqi_ct3slice");
        const fs::path dir = test::kRealData / "dcmqi_ct3slice";
        QTemporaryDir here;
        StudyStore store(here.path().toStdString());
        for (const char* name : {"01.dcm", "02.dcm", "03.dcm"}) {
            QVERIFY(test::storeCopy(store, dir / name, "CT"));
        }
        QVERIFY(test::storeCopy(store, dir / "liver_seg.dcm", "SEG"));
        const Volume ct = loadPath(dir);
        const std::string ctSeries = "1.2.392.200103.20080913.113635.1.2009.6.22.21.43.10.23430.1";
        SegmentationArchive archive(store);
        const auto loaded = archive.load(ctSeries, ct.geometry());
        QVERIFY(loaded.errors.empty());
        QCOMPARE(loaded.loaded.size(), std::size_t(1));
        QVERIFY(!loaded.loaded.front().segmentation.header.writtenByLucent);
        QCOMPARE(loaded.loaded.front().segmentation.segments.front().name, std::string("Liver"));
    }

    void cliWritesAndReadsASeg() {
        QTemporaryDir dir;
        const QString ct = QString::fromStdString((test::kRealData / test::kSegmentedCt).string());
        const QString out = dir.filePath("bone.dcm");
        const test::CliRun run = test::runCli({"segment", ct, "--threshold", "300,3000",
                                               "--keep-largest", "--name", "Skull", "-o", out});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const SegmentMask expected = keepLargestIsland(thresholdMask(ct_, 300.0, 3000.0));
        const ReadSegmentationDicom read =
            readSegmentationDicom(out.toStdString(), series_, ct_.geometry());
        QCOMPARE(read.segments.size(), std::size_t(1));
        QVERIFY(*read.segments.front().mask == expected);
        QCOMPARE(read.segments.front().algorithmName, std::string("Lucent threshold"));

        const test::CliRun stats = test::runCli({"segment-stats", ct, out});
        QVERIFY2(stats.exitCode == 0, qPrintable(stats.err));
        QVERIFY2(stats.out.contains("number=1 label=\"Skull\""), qPrintable(stats.out));
        const SegmentStatistics s = segmentStatistics(expected, ct_);
        QCOMPARE(test::statOf(stats.out, "voxels"), double(s.voxels));

        const QString none = dir.filePath("none.dcm");
        const test::CliRun empty =
            test::runCli({"segment", ct, "--threshold", "9000,9001", "-o", none});
        QCOMPARE(empty.exitCode, 3);
        QVERIFY(!QFile::exists(none));

        const test::CliRun wrong = test::runCli({"segment-stats", ct, ct + "/I10"});
        QCOMPARE(wrong.exitCode, 3);
        QVERIFY2(wrong.err.contains("I10: not a DICOM Segmentation"), qPrintable(wrong.err));
    }
};

QTEST_GUILESS_MAIN(TestSegmentationArchive)
#include "test_segmentation_archive.moc"
