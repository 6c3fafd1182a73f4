// lucent-cli segment and segment-stats on the real CT: the labelmap written is the
// threshold's largest island voxel for voxel on the CT's grid, --stats agrees with the
// statistics computed here, nothing is written for an empty result (exit 3), bad flags exit 2;
// a NIfTI labelmap of two labels reads back into two segments.
#include <QTemporaryDir>
#include <QTest>

#include "core/formats/Nifti.h"
#include "core/formats/NiftiWrite.h"
#include "core/io/Catalog.h"
#include "core/segmentation/Labelmap.h"
#include "core/segmentation/SegmentEffects.h"
#include "core/segmentation/SegmentStatistics.h"
#include "tests/support/CliRunner.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {
constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";
}

class TestSegmentCli : public QObject {
    Q_OBJECT

    QTemporaryDir dir_;
    QString ct_;
    Volume volume_;

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        ct_ = QString::fromStdString((test::kRealData / kCt).string());
        volume_ = loadPath(test::kRealData / kCt);
    }

    void writesTheLargestIslandAsALabelmap() {
        const QString out = dir_.filePath("bone.nii.gz");
        const test::CliRun run =
            test::runCli({"segment", ct_, "--threshold", "300,3000", "--keep-largest", "--name",
                          "Skeleton", "-o", out, "--stats"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const SegmentMask expected = keepLargestIsland(thresholdMask(volume_, 300.0, 3000.0));
        const Volume labels = readNifti(out.toStdString());
        QCOMPARE(labels.dims(), volume_.dims());
        const VolumeGeometry& a = labels.geometry();
        const VolumeGeometry& b = volume_.geometry();
        QVERIFY(glm::length(a.origin - b.origin) < 1e-3);
        QVERIFY(glm::length(a.spacing - b.spacing) < 1e-5);
        for (int c = 0; c < 3; ++c) {
            QVERIFY(glm::length(a.direction[c] - b.direction[c]) < 1e-5);
        }
        std::size_t set = 0;
        for (int k = 0; k < 28; ++k) {
            for (int j = 0; j < 512; ++j) {
                for (int i = 0; i < 512; ++i) {
                    const double v = labels.value(i, j, k);
                    QVERIFY(v == 0.0 || v == 1.0);
                    if ((v == 1.0) != expected.at(i, j, k)) {
                        QFAIL(qPrintable(QString("voxel %1 %2 %3").arg(i).arg(j).arg(k)));
                    }
                    set += v == 1.0;
                }
            }
        }
        QCOMPARE(set, expected.count());
        const SegmentStatistics s = segmentStatistics(expected, volume_);
        QCOMPARE(test::statOf(run.out, "voxels"), double(s.voxels));
        QVERIFY(std::abs(test::statOf(run.out, "volume_ml") - s.volumeMl) < 1e-4);
        QVERIFY(std::abs(test::statOf(run.out, "mean") - s.mean) < 1e-3);

        // segment-stats reads it back: the same numbers.
        const test::CliRun stats = test::runCli({"segment-stats", ct_, out});
        QVERIFY2(stats.exitCode == 0, qPrintable(stats.err));
        QVERIFY(stats.out.contains("label=\"Label 1\""));
        QCOMPARE(test::statOf(stats.out, "voxels"), double(s.voxels));
        QVERIFY(std::abs(test::statOf(stats.out, "diameter_mm") - s.largestDiameterMm) < 0.01);
    }

    void marginAndIslandsFromTheCommandLine() {
        const QString out = dir_.filePath("grown.nii");
        const test::CliRun run =
            test::runCli({"segment", ct_, "--threshold", "300,3000", "--min-island-mm3", "100",
                          "--margin", "2", "-o", out});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const VolumeGeometry& g = volume_.geometry();
        const SegmentMask expected =
            marginMask(removeSmallIslands(thresholdMask(volume_, 300.0, 3000.0), g, 100.0), g, 2.0);
        const Volume labels = readNifti(out.toStdString());
        Segmentation read(g);
        importLabelmap(read, labels);
        QCOMPARE(read.segments().size(), std::size_t{1});
        QVERIFY(*read.segments()[0].mask == expected);
    }

    void refusesWhatItCannotDo() {
        const QString out = dir_.filePath("none.nii.gz");
        const test::CliRun empty =
            test::runCli({"segment", ct_, "--threshold", "50000,60000", "-o", out});
        QCOMPARE(empty.exitCode, 3);
        QVERIFY(empty.err.contains("no voxel"));
        QVERIFY(!QFile::exists(out));
        QCOMPARE(test::runCli({"segment", ct_, "--threshold", "300", "-o", out}).exitCode, 2);
        QCOMPARE(
            test::runCli({"segment", ct_, "--threshold", "300,400", "-o", dir_.filePath("x.png")})
                .exitCode,
            2);
        QCOMPARE(test::runCli({"segment", ct_, "--threshold", "300,400", "--keep-largest",
                               "--min-island-mm3", "5", "-o", out})
                     .exitCode,
                 2);
        // A labelmap on another grid: named, exit 3.
        VolumeGeometry other;
        other.dims = {4, 4, 4};
        Volume small(other, VoxelType::Int16);
        const QString wrong = dir_.filePath("small.nii");
        writeNifti(wrong.toStdString(), small);
        const test::CliRun stats = test::runCli({"segment-stats", ct_, wrong});
        QCOMPARE(stats.exitCode, 3);
        QVERIFY(stats.err.contains("small.nii"));
    }

    void labelmapRoundTripKeepsSegments() {
        Segmentation seg(volume_.geometry());
        const std::uint32_t bone = seg.add("Bone", findSegmentKind("bone"));
        const std::uint32_t air = seg.add("Air");
        seg.setMask(bone, thresholdMask(volume_, 300.0, 3000.0), "Threshold");
        seg.setMask(air, thresholdMask(volume_, -2000.0, -900.0), "Threshold");
        const QString file = dir_.filePath("two.nii.gz");
        writeNifti(file.toStdString(), labelmapOf(seg));
        Segmentation back(volume_.geometry());
        const auto ids = importLabelmap(back, readNifti(file.toStdString()), {"Bone", "Air"});
        QCOMPARE(ids.size(), std::size_t{2});
        QCOMPARE(back.find(ids[0])->name, std::string("Bone"));
        QVERIFY(*back.find(ids[0])->mask == *seg.find(bone)->mask);
        QVERIFY(*back.find(ids[1])->mask == *seg.find(air)->mask);
    }
};

QTEST_GUILESS_MAIN(TestSegmentCli)
#include "test_segment_cli.moc"
