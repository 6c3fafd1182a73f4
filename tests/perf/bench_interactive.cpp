// Benchmark (label perf): lucent-cli bench interactive in full on the Philips 140-slice CT,
// issue 31's goal table with the VTK and VolPack anchors side by side (three runs): the
// tiled 512^3 cube at 1024x1024, 512 x 512 x 5382 in 2 GiB, a surface of 700k triangles,
// Lucent against VTK's GPU and fixed-point mappers and VolPack, memory and the time outside
// the cast. Prints the table (and writes build/bench_interactive.csv); fails when a row could
// not be measured (an anchor missing names its package), never on a goal missed.
#include <QTest>

#include "tests/support/CliRunner.h"
#include "tests/support/InteractiveTable.h"
#include "tests/support/RealData.h"

using namespace lucent;

class BenchInteractive : public QObject {
    Q_OBJECT
private slots:
    void philipsCt() {
        const char* ct = "dcm_qa_ct/Philips_S21570/S2020";
        REQUIRE_DATA(ct);
        const QString csv = QString(LUCENT_BIN_DIR) + "/../bench_interactive.csv";
        const test::CliRun r =
            test::runCli({"bench", "interactive",
                          QString::fromStdString((test::kRealData / ct).string()), "--csv", csv},
                         3 * 3600 * 1000);
        qInfo("%s", qPrintable(r.out));
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QList<test::InteractiveTableRow> rows = test::interactiveTableRows(r.out);
        QCOMPARE(rows.size(), 6 + 2 + 1 + 2 * 3 * 3 + 3);
        for (const test::InteractiveTableRow& row : rows) {
            for (const QString& cell : {row.lucent, row.anchor}) {
                QVERIFY2(!cell.startsWith("failed") && !cell.startsWith("not ") &&
                             !cell.startsWith("no GL device"),
                         qPrintable(row.what + ": " + cell));
            }
        }
    }
};

int main(int argc, char** argv) {
    // The full table takes long on llvmpipe; QtTest stops a test function after 5 minutes.
    if (qEnvironmentVariableIsEmpty("QTEST_FUNCTION_TIMEOUT")) {
        qputenv("QTEST_FUNCTION_TIMEOUT", "11000000");
    }
    BenchInteractive bench;
    return QTest::qExec(&bench, argc, argv);
}
#include "bench_interactive.moc"
