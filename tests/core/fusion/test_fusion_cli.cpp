// lucent-cli convert and render with --overlay on the real 28-slice CT and a copy of it
// whose ImagePositionPatient moved by a known shift into a new Frame of Reference
// (writePriorStudy, DCMTK): base -> overlay is x + shift, so the overlay resampled through
// that transform is the CT again, voxel for voxel; through the opposite shift it is not.
// render --overlay differs from the plain render and equals it at --overlay-opacity 0.
// transform.json's reader (core/fusion/TransformFile) refuses bad files naming the file
// and the field; a missing --transform between two Frames of Reference names both.
#include <QFile>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>

#include "core/formats/MetaImage.h"
#include "core/fusion/TransformFile.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "tests/support/CliRunner.h"
#include "tests/support/PriorStudy.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";
const glm::dvec3 kShift(12.5, -30.0, 8.0);

QString matrixJson(const glm::dvec3& t) {
    return QString(R"({"matrix": [[1, 0, 0, %1], [0, 1, 0, %2], [0, 0, 1, %3], [0, 0, 0, 1]]})")
        .arg(t.x)
        .arg(t.y)
        .arg(t.z);
}

} // namespace

class TestFusionCli : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    QString ct_, moved_, transform_;
    Volume ctVolume_;
    std::string movedFrame_;

    QString write(const QString& name, const QString& text) {
        const QString path = dir_.filePath(name);
        QFile f(path);
        if (!f.open(QIODevice::WriteOnly) || f.write(text.toUtf8()) < 0) {
            qFatal("cannot write %s", qPrintable(path));
        }
        return path;
    }

    // Voxels of `mhd` that differ from the CT's by more than `tolerance`, and the largest
    // difference.
    std::pair<std::size_t, double> differences(const QString& mhd, double tolerance) {
        const Volume out = readMetaImage(mhd.toStdString());
        if (out.dims() != ctVolume_.dims() || out.type() != VoxelType::Float32) {
            return {std::size_t(-1), HUGE_VAL};
        }
        const auto values = out.voxels<float>();
        const auto ct = ctVolume_.voxels<std::int16_t>();
        std::size_t count = 0;
        double worst = 0.0;
        for (std::size_t i = 0; i < values.size(); ++i) {
            const double d = std::abs(double(values[i]) - double(ct[i]));
            worst = std::max(worst, d);
            count += d > tolerance ? 1 : 0;
        }
        return {count, worst};
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        QVERIFY(dir_.isValid());
        ct_ = QString::fromStdString((test::kRealData / kCt).string());
        const test::PriorStudy moved = test::writePriorStudy(
            test::kRealData / kCt, dir_.filePath("moved").toStdString(), "20240101", kShift);
        moved_ = dir_.filePath("moved");
        movedFrame_ = moved.frameOfReferenceUid;
        transform_ = write("transform.json", matrixJson(kShift));
        ctVolume_ = loadPath(test::kRealData / kCt);
        QCOMPARE(ctVolume_.type(), VoxelType::Int16);
        QVERIFY(ctVolume_.frameOfReferenceUid != movedFrame_);
    }

    void convertGivesTheCtBackThroughTheTransform() {
        const QString out = dir_.filePath("overlay.mhd");
        const test::CliRun run =
            test::runCli({"convert", ct_, out, "--overlay", moved_, "--transform", transform_});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const auto [count, worst] = differences(out, 0.01);
        qInfo("through the transform: %zu voxels off by more than 0.01 HU, worst %g", count, worst);
        QCOMPARE(count, std::size_t(0));

        // The opposite shift: the overlay 2 * shift away, off in most of the head.
        const QString wrong = write("wrong.json", matrixJson(-kShift));
        const QString outWrong = dir_.filePath("wrong.mhd");
        QCOMPARE(test::runCli({"convert", ct_, outWrong, "--overlay", moved_, "--transform", wrong})
                     .exitCode,
                 0);
        const std::size_t off = differences(outWrong, 10.0).first;
        QVERIFY2(off > ctVolume_.geometry().voxelCount() / 10, qPrintable(QString::number(off)));
    }

    void renderShowsTheOverlayAndOpacityZeroDoesNot() {
        const QStringList common = {"render", ct_, "--size", "128x128", "--azimuth", "30"};
        const QString plain = dir_.filePath("plain.png"), fused = dir_.filePath("fused.png"),
                      zero = dir_.filePath("zero.png");
        const QStringList overlay = {"--overlay",        moved_,    "--transform",   transform_,
                                     "--overlay-window", "300,400", "--overlay-map", "hot-iron"};
        test::CliRun run = test::runCli(common + QStringList{"-o", plain});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        run = test::runCli(common + overlay + QStringList{"-o", fused, "--overlay-opacity", "0.6"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        run = test::runCli(common + overlay + QStringList{"-o", zero, "--overlay-opacity", "0"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const ImageRGBA8 a = readPng(plain.toStdString()), b = readPng(fused.toStdString()),
                         c = readPng(zero.toStdString());
        QVERIFY(a.pixels == c.pixels);
        const double p = psnr(a, b);
        qInfo("plain against fused: %.2f dB", p);
        QVERIFY2(p < 35.0, qPrintable(QString::number(p)));
        // The GL backend draws the same overlay (llvmpipe here).
        const QString gl = dir_.filePath("gl.png");
        run = test::runCli(common + overlay +
                           QStringList{"-o", gl, "--overlay-opacity", "0.6", "--backend", "gl"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        if (!run.err.contains("rendering on the CPU instead")) {
            const double g = psnr(readPng(gl.toStdString()), b);
            QVERIFY2(g >= 50.0, qPrintable(QString("gl against cpu: %1 dB").arg(g)));
        }
    }

    void missingTransformNamesBothFramesOfReference() {
        const test::CliRun run =
            test::runCli({"convert", ct_, dir_.filePath("none.mhd"), "--overlay", moved_});
        QCOMPARE(run.exitCode, 3);
        QVERIFY2(run.err.contains(QString::fromStdString(ctVolume_.frameOfReferenceUid)) &&
                     run.err.contains(QString::fromStdString(movedFrame_)) &&
                     run.err.contains("--transform"),
                 qPrintable(run.err));
        // One Frame of Reference: the identity needs no file.
        const test::CliRun same = test::runCli(
            {"render", ct_, "-o", dir_.filePath("same.png"), "--size", "64x64", "--overlay", ct_});
        QVERIFY2(same.exitCode == 0, qPrintable(same.err));
    }

    void badTransformFilesAreRefusedByName_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("says");
        QTest::newRow("not json") << "{matrix"
                                  << "not JSON";
        QTest::newRow("no matrix") << R"({"metric": 0.5})"
                                   << "no \"matrix\"";
        QTest::newRow("three rows") << R"({"matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0]]})"
                                    << "not 4 rows of 4";
        QTest::newRow("short row") << R"({"matrix": [[1,0,0,0],[0,1,0],[0,0,1,0],[0,0,0,1]]})"
                                   << "row 1 is not 4 numbers";
        QTest::newRow("text") << R"({"matrix": [[1,0,0,0],[0,1,0,0],[0,0,"x",0],[0,0,0,1]]})"
                              << "[2][2] is not a finite number";
        QTest::newRow("projective") << R"({"matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,1,1]]})"
                                    << "row 3 is not 0 0 0 1";
        QTest::newRow("singular") << R"({"matrix": [[1,0,0,0],[0,1,0,0],[0,0,0,0],[0,0,0,1]]})"
                                  << "singular";
    }
    void badTransformFilesAreRefusedByName() {
        QFETCH(QString, text);
        QFETCH(QString, says);
        const QString file = write("bad.json", text);
        for (const char* command : {"convert", "render"}) {
            const QString out =
                dir_.filePath(command == std::string("convert") ? "bad.mhd" : "bad.png");
            const QStringList args =
                command == std::string("convert")
                    ? QStringList{command, ct_, out, "--overlay", moved_, "--transform", file}
                    : QStringList{command,     ct_,    "-o",          out,
                                  "--overlay", moved_, "--transform", file};
            const test::CliRun run = test::runCli(args);
            QCOMPARE(run.exitCode, 3);
            QVERIFY2(run.err.contains(file) && run.err.contains(says), qPrintable(run.err));
        }
        QVERIFY_THROWS_EXCEPTION(TransformFileError, readTransformFile(file.toStdString()));
    }

    void missingTransformFileIsNamed() {
        const QString file = dir_.filePath("absent.json");
        const test::CliRun run = test::runCli(
            {"convert", ct_, dir_.filePath("x.mhd"), "--overlay", moved_, "--transform", file});
        QCOMPARE(run.exitCode, 3);
        QVERIFY2(run.err.contains(file) && run.err.contains("cannot read"), qPrintable(run.err));
    }

    void overlayFlagsNeedAnOverlay() {
        for (const QStringList& extra :
             {QStringList{"--overlay-opacity", "0.5"}, QStringList{"--transform", transform_},
              QStringList{"--overlay-map", "pet"}, QStringList{"--overlay-series", "1"}}) {
            const test::CliRun run =
                test::runCli(QStringList{"render", ct_, "-o", dir_.filePath("n.png")} + extra);
            QCOMPARE(run.exitCode, 2);
            QVERIFY2(run.err.contains("needs --overlay"), qPrintable(run.err));
        }
        const test::CliRun bad = test::runCli({"render", ct_, "-o", dir_.filePath("n.png"),
                                               "--overlay", ct_, "--overlay-window", "40"});
        QCOMPARE(bad.exitCode, 2);
        QVERIFY2(bad.err.contains("--overlay-window"), qPrintable(bad.err));
    }

    // What register writes, render reads: the writer and the reader are one file's.
    void writtenTransformsReadBack() {
        glm::dmat4 m(1.0);
        m[0] = glm::dvec4(0.98, 0.17, 0.0, 0.0);
        m[1] = glm::dvec4(-0.17, 0.98, 0.0, 0.0);
        m[3] = glm::dvec4(1.5, -2.25, 3.125, 1.0);
        const std::string file = dir_.filePath("written.json").toStdString();
        writeTransformFile(
            file, m,
            TransformFileFacts{"Mattes MI", -0.5, 12, 1.5, true, "ok", "rigid", "centres"});
        QVERIFY(readTransformFile(file) == m);
    }
};

QTEST_GUILESS_MAIN(TestFusionCli)
#include "test_fusion_cli.moc"
