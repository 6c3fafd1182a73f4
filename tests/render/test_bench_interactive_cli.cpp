// lucent-cli bench interactive on the real CT, shrunk to run in seconds on llvmpipe: every
// row of issue 31's table is there, with a figure or the reason it has none (the anchors
// skipped, the long volume skipped, no GL device), the CSV holds the same rows, and a bad
// option is refused naming it.
#include <QFile>
#include <QTemporaryDir>
#include <QTest>

#include "tests/support/CliRunner.h"
#include "tests/support/InteractiveTable.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

const char* kCt = "dcm_qa_ct/Philips_S21570/S2020";

QString ct() {
    return QString::fromStdString((test::kRealData / kCt).string());
}

// What the small run's rows start with, in order.
const QStringList kRows = {
    "GL 96x96x96 (tiled), 48x48, tricubic + shading, opacity per voxel",
    "GL 96x96x96 (tiled), 48x48, tricubic + shading + pre-integration, opacity per voxel",
    "GL 96x96x96 (tiled), 48x48, trilinear + shading, opacity per voxel",
    "GL 96x96x96 (tiled), 48x48, tricubic + shading, opacity per mm",
    "GL 96x96x96 (tiled), 48x48, tricubic + shading + pre-integration, opacity per mm",
    "GL 96x96x96 (tiled), 48x48, trilinear + shading, opacity per mm",
    "GL 512x512x5382 (tiled) in 2048 MiB, 64x64: first frame after load",
    "GL 512x512x5382 (tiled) in 2048 MiB, 64x64: frames a second",
    "GL with a surface of ~20000 triangles",
    "GL vs VTK GPU mapper, run 1/1, opacity per voxel",
    "CPU vs VTK fixed-point, run 1/1, opacity per voxel",
    "CPU vs VolPack shear-warp (parallel projection), run 1/1, opacity per voxel",
    "GL vs VTK GPU mapper, run 1/1, opacity per mm",
    "CPU vs VTK fixed-point, run 1/1, opacity per mm",
    "CPU vs VolPack shear-warp (parallel projection), run 1/1, opacity per mm",
    "GL default path: GPU memory",
    "GL: CPU time outside the cast",
    "CPU caster: time outside the cast",
};

} // namespace

class TestBenchInteractiveCli : public QObject {
    Q_OBJECT
private slots:
    void everyRowHasAFigureOrAReason() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        const QString csv = dir.filePath("rows.csv");
        const test::CliRun r =
            test::runCli({"bench", "interactive", ct(), "--no-anchors", "--runs", "1", "--size",
                          "64x64", "--cube", "96", "--cube-size", "48x48", "--skip-large",
                          "--surface-triangles", "20000", "--csv", csv},
                         240000);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(r.out.contains("\nGL renderer: "), qPrintable(r.out));
        QVERIFY2(r.out.contains("\nCPU caster: "), qPrintable(r.out));
        const QList<test::InteractiveTableRow> rows = test::interactiveTableRows(r.out);
        QCOMPARE(rows.size(), kRows.size());
        const bool gl = !r.out.contains("GL renderer: none");
        for (int n = 0; n < rows.size(); ++n) {
            const test::InteractiveTableRow& row = rows[n];
            const QString said = row.what + " | " + row.lucent + " | " + row.anchor;
            QVERIFY2(row.what.startsWith(kRows[n]), qPrintable(kRows[n] + " <- " + said));
            QVERIFY2((!row.goal.isEmpty() && row.goal != "-") || row.what.contains("VolPack"),
                     qPrintable(said));
            if (row.what.startsWith("GL 512x512x5382")) {
                QCOMPARE(row.lucent, QString("skipped (--skip-large)"));
            } else if (row.what.startsWith("GL") && !gl) {
                QVERIFY2(row.lucent.startsWith("no GL device: "), qPrintable(said));
            } else {
                QVERIFY2(test::holdsFigure(row.lucent), qPrintable(said));
                QVERIFY2(row.met == "yes" || row.met == "no" || row.what.contains(" vs "),
                         qPrintable(said));
            }
            if (row.what.contains(" vs ")) {
                QCOMPARE(row.anchor, QString("skipped (--no-anchors)"));
                QCOMPARE(row.ratio, QString("-"));
                QCOMPARE(row.met, QString("-"));
            }
        }
        QFile f(csv);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QStringList lines = QString::fromUtf8(f.readAll()).trimmed().split('\n');
        QCOMPARE(lines.front(), QString("what,lucent,anchor,ratio,goal,met"));
        QCOMPARE(lines.size(), 1 + kRows.size());
        QVERIFY2(lines[1].startsWith('"' + kRows[0]), qPrintable(lines[1]));
    }

    void badOptionsAreRefusedNamingThem() {
        const QList<QPair<QStringList, QString>> bad = {
            {{"--bogus"}, "bogus"},
            {{"--runs", "0"}, "--runs"},
            {{"--size", "big"}, "--size"},
            {{"--cube", "x"}, "--cube"},
            {{"--long-dims", "512x512"}, "--long-dims"},
            {{"--units", "furlong"}, "--units"},
            {{"--surface-iso", "hot"}, "--surface-iso"},
        };
        for (const auto& [options, named] : bad) {
            const test::CliRun r = test::runCli(QStringList{"bench", "interactive", "x"} + options);
            QVERIFY2(r.exitCode == 2, qPrintable(options.join(' ') + ": " + r.err));
            QVERIFY2(r.err.contains(named), qPrintable(options.join(' ') + ": " + r.err));
        }
        const test::CliRun none = test::runCli({"bench", "interactive"});
        QCOMPARE(none.exitCode, 2);
        const test::CliRun missing =
            test::runCli({"bench", "interactive", "/nonexistent/volume.mhd", "--no-anchors"});
        QVERIFY2(missing.exitCode == 3, qPrintable(missing.err));
        QVERIFY2(missing.err.contains("/nonexistent/volume.mhd"), qPrintable(missing.err));
    }
};

QTEST_GUILESS_MAIN(TestBenchInteractiveCli)
#include "test_bench_interactive_cli.moc"
