// ui/segmentation/SegmentationAutosave on a real study store holding the real CT: an edit of
// the tracked Segmentation is saved as Lucent's SEG after the debounce delay (found by the
// poll of revision(), no call needed), the next edit replaces it, detach() saves what is
// pending, load() brings it back; a series outside the store is kept for the session only.
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include "core/segdicom/SegmentationArchive.h"
#include "tests/core/report/StoredCopies.h"
#include "tests/core/segdicom/SegmentedCt.h"
#include "ui/segmentation/SegmentationAutosave.h"

using namespace lucent;
namespace fs = std::filesystem;

class TestSegmentationAutosave : public QObject {
    Q_OBJECT

private slots:
    void savesAfterEditsAndLoadsBack() {
        REQUIRE_DATA(test::kSegmentedCt);
        QTemporaryDir here;
        std::string seriesUid;
        {
            StudyStore store(here.path().toStdString());
            for (const fs::path& file : test::segmentedCtFiles()) {
                QVERIFY(test::storeCopy(store, file, "CT"));
            }
            seriesUid = store.listSeries().front().info.seriesUid;
        }
        const Volume ct = loadPath(test::kRealData / test::kSegmentedCt);
        Segmentation seg(ct.geometry());
        SegmentationAutosave autosave(here.path());
        QSignalSpy saved(&autosave, &SegmentationAutosave::saved);
        QSignalSpy messages(&autosave, &SegmentationAutosave::message);
        QVERIFY(autosave.attach(&seg, QString::fromStdString(seriesUid)));
        QVERIFY(messages.isEmpty());

        const std::uint32_t bone = seg.add("Skull", findSegmentKind("bone"));
        seg.setMask(bone, thresholdMask(ct, 300.0, 3000.0), "Threshold", "Lucent threshold");
        QTRY_COMPARE_WITH_TIMEOUT(saved.size(), 1, 10000);
        const QString first = saved.at(0).at(1).toString();
        QVERIFY(!first.isEmpty());

        seg.rename(bone, "Cranium");
        autosave.changed();
        QTRY_COMPARE_WITH_TIMEOUT(saved.size(), 2, 10000);
        QVERIFY(saved.at(1).at(1).toString() != first);

        seg.setColour(bone, {10, 200, 30});
        autosave.detach(&seg); // saved at once
        QCOMPARE(saved.size(), 3);
        QTest::qWait(SegmentationAutosave::kDelayMs + 300);
        QCOMPARE(saved.size(), 3); // no longer tracked

        const SegmentationArchive::LoadResult loaded =
            autosave.load(QString::fromStdString(seriesUid), ct.geometry());
        QVERIFY(loaded.errors.empty());
        QCOMPARE(loaded.loaded.size(), std::size_t(1)); // the SEG was replaced, not added
        const Segment& read = loaded.loaded.front().segmentation.segments.front();
        QCOMPARE(read.name, std::string("Cranium"));
        QVERIFY(read.colour == (std::array<std::uint8_t, 3>{10, 200, 30}));
        QVERIFY(*read.mask == *seg.segments().front().mask);
        QVERIFY(messages.isEmpty());

        Segmentation other(ct.geometry());
        QVERIFY(!autosave.attach(&other, "1.2.3.4"));
        QCOMPARE(messages.size(), 1);
    }
};

QTEST_GUILESS_MAIN(TestSegmentationAutosave)
#include "test_segmentation_autosave.moc"
