// lucent-cli surface on real CT, as a user runs it: the demo skull (InVesalius'
// Cranium, 226 HU) is closed with the research note's triangle count and
// volume; a clipped Philips CT gets its surface-to-volume field written to a
// PLY whose svr values match the --stats line; bad input is refused with the
// reason and the exit status of the other commands.
#include <QFile>
#include <QFileInfo>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTest>

#include <cstring>

#include "tests/support/CliRunner.h"

using namespace lucent::test;

namespace {

const QString kSkull = "/usr/share/doc/invesalius-examples/examples/Cranium.inv3";
const QString kCt = LUCENT_TEST_DATA_DIR "/dcm_qa_ct/Philips_S21570/S2010";

} // namespace

class TestSurfaceCli : public QObject {
    Q_OBJECT
    QTemporaryDir tmp_;
    QString path(const QString& name) const { return tmp_.filePath(name); }

private slots:
    void initTestCase() {
        if (!QFileInfo::exists(kSkull)) {
            QFAIL(
                "the demo CT is missing: install invesalius-examples (packaging/install-deps.sh)");
        }
        if (!QFileInfo::exists(kCt)) {
            QSKIP("the Philips CT is not in ../shared/data");
        }
    }

    // 678,480 triangles and 661.6 cm³ (InVesalius' own surface: 657.7 cm³).
    void theDemoSkullIsClosed() {
        const CliRun r =
            runCli({"surface", kSkull, "-o", path("skull.stl"), "--iso", "226", "--stats"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(statOf(r.out, "watertight"), 1.0);
        QCOMPARE(statOf(r.out, "triangles"), 678480.0);
        QVERIFY2(std::abs(statOf(r.out, "volume_mm3") / 661632.0 - 1.0) < 1e-3, qPrintable(r.out));
        QCOMPARE(QFileInfo(path("skull.stl")).size(), qint64(84 + 50 * 678480));
    }

    void theFieldGoesIntoThePly() {
        const CliRun r = runCli({"surface", kCt, "-o", path("ct.ply"), "--iso", "300", "--clip",
                                 "150,150,0,350,350,27", "--svr-radius", "2", "--largest", "3",
                                 "--smooth", "10", "--stats"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        for (const char* key : {"triangles", "vertices", "area_mm2", "volume_mm3", "watertight",
                                "components", "components_dropped", "extract_ms", "svr_ms",
                                "svr_mean", "svr_p05", "svr_p95", "h_max_over_r"}) {
            QVERIFY2(!std::isnan(statOf(r.out, key)), key);
        }
        QCOMPARE(statOf(r.out, "watertight"), 1.0);
        QCOMPARE(statOf(r.out, "components"), 3.0);
        QVERIFY(statOf(r.out, "components_dropped") > 0.0);
        const double p05 = statOf(r.out, "svr_p05"), p95 = statOf(r.out, "svr_p95");
        QVERIFY(p05 > 0.0 && p05 < p95);
        // The PLY's svr values: their mean is the --stats line's.
        QFile ply(path("ct.ply"));
        QVERIFY(ply.open(QIODevice::ReadOnly));
        const QByteArray bytes = ply.readAll();
        const qsizetype end = bytes.indexOf("end_header\n") + 11;
        const auto vertices =
            QRegularExpression("element vertex (\\d+)").match(QString::fromLatin1(bytes.left(end)));
        const qsizetype n = vertices.captured(1).toLongLong();
        QCOMPARE(double(n), statOf(r.out, "vertices"));
        double sum = 0.0;
        for (qsizetype v = 0; v < n; ++v) {
            float svr = 0.0f;
            std::memcpy(&svr, bytes.constData() + end + v * 35 + 31, 4);
            sum += svr;
        }
        QVERIFY2(std::abs(sum / double(n) / statOf(r.out, "svr_mean") - 1.0) < 1e-4,
                 qPrintable(r.out));
    }

    void badInputSaysWhy_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<int>("status");
        QTest::addColumn<QString>("says");
        QTest::newRow("iso outside the values")
            << QStringList{"--iso", "99999"} << 3 << "outside the volume's value range";
        QTest::newRow("nothing in the clip box")
            << QStringList{"--iso", "300", "--clip", "0,0,0,10,10,5"} << 3 << "no surface";
        QTest::newRow("no iso") << QStringList{} << 2 << "--iso";
        QTest::newRow("both filters")
            << QStringList{"--iso", "300", "--largest", "1", "--min-component-voxels", "5"} << 2
            << "exclude each other";
        QTest::newRow("negative radius")
            << QStringList{"--iso", "300", "--svr-radius", "-1"} << 3 << "radius";
    }
    void badInputSaysWhy() {
        QFETCH(QStringList, args);
        QFETCH(int, status);
        QFETCH(QString, says);
        const CliRun r = runCli(QStringList{"surface", kCt, "-o", path("bad.stl")} + args);
        QCOMPARE(r.exitCode, status);
        QVERIFY2(r.err.contains(says), qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(path("bad.stl")));
    }

    void anUnknownExtensionIsAUsageError() {
        const CliRun r = runCli({"surface", kCt, "-o", path("x.3mf"), "--iso", "300"});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains(".stl, .ply, .vtk or .obj"), qPrintable(r.err));
    }

    void stlWithAFieldSaysItCannotHoldIt() {
        const CliRun r = runCli({"surface", kCt, "-o", path("f.stl"), "--iso", "300", "--clip",
                                 "200,200,0,300,300,27", "--svr-radius", "3"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(r.err.contains("STL holds no per-vertex values"), qPrintable(r.err));
    }
};

QTEST_GUILESS_MAIN(TestSurfaceCli)
#include "test_surface_cli.moc"
