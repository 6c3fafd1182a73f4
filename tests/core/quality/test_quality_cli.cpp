// lucent-cli render --quality on a real CT: the front is measured once for the
// volume and backend and then read from the cache; fast renders settings no
// slower than best; both are on the measured front; the image is the one the
// chosen settings give; an unreachable target falls back to the fastest with
// a message; bad values are refused.
#include <QDir>
#include <QFile>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTest>

#include "tests/support/CliRunner.h"

using namespace lucent;

namespace {

const QString kSeries = QStringLiteral(LUCENT_TEST_DATA_DIR "/dcm_qa_ct/Philips_S21570/S2010");

QMap<QString, QString> stats(const QString& out) {
    QMap<QString, QString> m;
    static const QRegularExpression pair("(\\w+)=(\"[^\"]*\"|\\S+)");
    for (auto it = pair.globalMatch(out); it.hasNext();) {
        const auto match = it.next();
        QString value = match.captured(2);
        if (value.startsWith('"')) {
            value = value.mid(1, value.size() - 2);
        }
        m[match.captured(1)] = value;
    }
    return m;
}

} // namespace

class TestQualityCli : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;

private slots:
    void initTestCase() {
        if (!QDir(kSeries).exists()) {
            QSKIP("real CT data absent (../shared/data/dcm_qa_ct)");
        }
        // The children's QStandardPaths cache dir: this test's own.
        qputenv("XDG_CACHE_HOME", dir_.filePath("cache").toUtf8());
    }

    void fastIsNoSlowerThanBestAndBothAreOnTheFront() {
        const QStringList common = {"render", kSeries, "--size", "256x256", "--stats"};
        const test::CliRun fast = test::runCli(
            common + QStringList{"-o", dir_.filePath("fast.png"), "--quality", "fast"}, 280000);
        QVERIFY2(fast.exitCode == 0, qPrintable(fast.err));
        QVERIFY2(fast.err.contains("measuring the quality front"), qPrintable(fast.err));
        const auto f = stats(fast.out);
        QCOMPARE(f["quality_front"], QString("measured"));
        const test::CliRun best = test::runCli(
            common + QStringList{"-o", dir_.filePath("best.png"), "--quality", "best"});
        QVERIFY2(best.exitCode == 0, qPrintable(best.err));
        const auto b = stats(best.out);
        QCOMPARE(b["quality_front"], QString("cached")); // same volume and backend
        QCOMPARE(b["quality_front_file"], f["quality_front_file"]);
        QVERIFY2(f["quality_predicted_ms"].toDouble() <= b["quality_predicted_ms"].toDouble(),
                 qPrintable(fast.out + best.out));
        QVERIFY2(f["quality_psnr_db"].toDouble() <= b["quality_psnr_db"].toDouble(),
                 qPrintable(fast.out + best.out));

        // Both chosen settings are rows of the measured front, marked on it.
        QFile csv(f["quality_front_file"]);
        QVERIFY2(csv.open(QIODevice::ReadOnly), qPrintable(csv.fileName()));
        const QStringList lines = QString::fromUtf8(csv.readAll()).trimmed().split('\n');
        QVERIFY(lines.size() > 5);
        QVERIFY2(lines[1].contains("backend=cpu") && lines[1].contains("shading=1"),
                 qPrintable(lines[1]));
        for (const auto& chosen : {f, b}) {
            bool found = false;
            for (const QString& line : lines.mid(3)) {
                const QStringList c = line.split(',');
                if (c.size() == 10 && c[0].toDouble() == chosen["quality_step"].toDouble() &&
                    c[1] == chosen["quality_interp"] && c[2] == chosen["quality_classification"]) {
                    QCOMPARE(c[9], QString("1"));
                    QCOMPARE(c[7].toDouble(), chosen["quality_psnr_db"].toDouble());
                    found = true;
                }
            }
            QVERIFY2(found, qPrintable(chosen["quality_step"] + " " + chosen["quality_interp"]));
        }

        // The fast image is the one its settings give when asked for by hand.
        QStringList manual = common + QStringList{"-o",       dir_.filePath("manual.png"),
                                                  "--step",   f["quality_step"],
                                                  "--interp", f["quality_interp"]};
        if (f["quality_classification"] == "pre") {
            manual << "--preclassify";
        } else if (f["quality_classification"] == "preintegrated") {
            manual << "--preintegrate";
        }
        QCOMPARE(test::runCli(manual).exitCode, 0);
        const test::CliRun same =
            test::runCli({"compare", dir_.filePath("fast.png"), dir_.filePath("manual.png")});
        QVERIFY2(same.out.contains("psnr_db=inf"), qPrintable(same.out + same.err));
    }

    void sharpPresetGetsItsOwnFrontAndPreintegration() {
        // ct-soft-tissue's steep ramps: post-classified trilinear at step 0.25
        // stays near 32 dB here; pre-integration reaches 41 dB at step 0.5.
        const QStringList common = {"render",  kSeries,    "--size",
                                    "256x256", "--preset", "ct-soft-tissue"};
        const test::CliRun balanced =
            test::runCli(common + QStringList{"-o", dir_.filePath("soft.png"), "--quality",
                                              "balanced", "--stats"},
                         280000);
        QVERIFY2(balanced.exitCode == 0, qPrintable(balanced.err));
        const auto b = stats(balanced.out);
        QCOMPARE(b["quality_front"], QString("measured")); // not the default preset's front
        QCOMPARE(b["quality_classification"], QString("preintegrated"));
        QVERIFY2(b["quality_psnr_db"].toDouble() >= 38.0, qPrintable(balanced.out));
        const test::CliRun reference = test::runCli(
            common + QStringList{"-o", dir_.filePath("soft_ref.png"), "--interp", "cubic", "--step",
                                 "0.0625", "--precision", "double"});
        QVERIFY2(reference.exitCode == 0, qPrintable(reference.err));
        const test::CliRun compared =
            test::runCli({"compare", dir_.filePath("soft.png"), dir_.filePath("soft_ref.png")});
        const double psnr = stats(compared.out)["psnr_db"].toDouble();
        qInfo("balanced ct-soft-tissue: %s, %.1f dB against the reference at 256x256",
              qPrintable(b["quality_step"] + " " + b["quality_interp"] + " " +
                         b["quality_classification"]),
              psnr);
        QVERIFY2(psnr >= 38.0, qPrintable(compared.out));
    }

    void unreachableTargetGivesTheFastestWithAMessage() {
        const test::CliRun r =
            test::runCli({"render", kSeries, "-o", dir_.filePath("t.png"), "--size", "256x256",
                          "--quality", "0.001ms", "--stats"},
                         280000);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(r.err.contains("using the fastest"), qPrintable(r.err));
        QCOMPARE(stats(r.out)["quality_within_budget"], QString("0"));
    }

    void badQualityIsRefused() {
        test::CliRun r =
            test::runCli({"render", kSeries, "-o", dir_.filePath("x.png"), "--quality", "quick"});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("'quick'"), qPrintable(r.err));
        r = test::runCli(
            {"render", kSeries, "-o", dir_.filePath("x.png"), "--quality", "fast", "--step", "1"});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("--step"), qPrintable(r.err));
    }
};

QTEST_GUILESS_MAIN(TestQualityCli)
#include "test_quality_cli.moc"
