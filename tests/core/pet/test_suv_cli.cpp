// `lucent-cli info` on PET series made from a real CT with DCMTK: the SUVbw factor when
// it computes, the reason naming the element when it does not, nothing for other modalities.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>

#include "tests/support/CliRunner.h"
#include "tests/support/PetFromCt.h"
#include "tests/support/RealData.h"

using namespace lucent::test;

namespace {

const char* const kCt = "dcm_qa_ct/Philips_S21570/S2010";

QJsonObject onlySeries(const CliRun& r) {
    const QJsonArray series = QJsonDocument::fromJson(r.out.toUtf8()).object()["series"].toArray();
    return series.size() == 1 ? series[0].toObject() : QJsonObject();
}

} // namespace

class TestSuvCli : public QObject {
    Q_OBJECT
private slots:
    // 75.5 kg, 370 MBq of 18F (6586.2 s) injected 3900 s before the series time.
    void infoShowsTheFactor() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        writePetFromCt(kRealData / kCt, dir.path().toStdString(), {});
        const double want = 75500.0 / (370e6 * std::pow(2.0, -3900.0 / 6586.2));
        const CliRun json = runCli({"info", dir.path(), "--json"});
        QCOMPARE(json.exitCode, 0);
        const QJsonObject e = onlySeries(json);
        QCOMPARE(e["modality"].toString(), QString("PT"));
        QVERIFY2(std::abs(e["suv_bw_factor"].toDouble() - want) <= 1e-12 * want,
                 qPrintable(json.out));
        QVERIFY(!e.contains("suv_bw_refused"));
        const CliRun table = runCli({"info", dir.path()});
        QCOMPARE(table.exitCode, 0);
        QVERIFY2(
            table.out.contains(QString("SUVbw: factor %1 (g/mL per Bq/mL)").arg(want, 0, 'g', 6)),
            qPrintable(table.out));
    }

    void infoSaysWhyNot() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        PetHeader h;
        h.units = "CNTS";
        writePetFromCt(kRealData / kCt, dir.path().toStdString(), h);
        const CliRun json = runCli({"info", dir.path(), "--json"});
        QCOMPARE(json.exitCode, 0);
        const QJsonObject e = onlySeries(json);
        QVERIFY(!e.contains("suv_bw_factor"));
        QVERIFY2(e["suv_bw_refused"].toString().startsWith("Units (0054,1001) is CNTS"),
                 qPrintable(json.out));
        const CliRun table = runCli({"info", dir.path()});
        QVERIFY2(table.out.contains("SUVbw: not computed: Units (0054,1001) is CNTS"),
                 qPrintable(table.out));
    }

    void ctHasNoSuv() {
        REQUIRE_DATA(kCt);
        const CliRun json =
            runCli({"info", QString::fromStdString((kRealData / kCt).string()), "--json"});
        QCOMPARE(json.exitCode, 0);
        const QJsonObject e = onlySeries(json);
        QCOMPARE(e["modality"].toString(), QString("CT"));
        QVERIFY(!e.contains("suv_bw_factor") && !e.contains("suv_bw_refused"));
    }
};

QTEST_GUILESS_MAIN(TestSuvCli)
#include "test_suv_cli.moc"
