// `lucent-cli info` on every set of ../shared/data gives the series and slice
// counts it gave before the structure walk learnt to read untidy files (issue
// 27): the counts are pinned, so a reader change that gains or loses a slice of
// real data shows here.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>

#include <algorithm>

#include "tests/support/CliRunner.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

// "kind:slices" of every series entry, sorted, and the number of skipped files.
struct Counts {
    QStringList series;
    int skipped = 0;
};

Counts infoCounts(const QString& path) {
    const test::CliRun r = test::runCli({"info", path, "--json"});
    if (r.exitCode != 0) {
        qWarning("lucent-cli info %s: status %d: %s", qPrintable(path), r.exitCode,
                 qPrintable(r.err));
        return {{QString("exit %1").arg(r.exitCode)}, -1};
    }
    const QJsonObject doc = QJsonDocument::fromJson(r.out.toUtf8()).object();
    Counts c;
    for (const QJsonValue s : doc["series"].toArray()) {
        const QJsonArray dims = s["dims"].toArray();
        c.series << QString("%1:%2").arg(s["kind"].toString()).arg(dims[2].toInt());
    }
    std::sort(c.series.begin(), c.series.end());
    c.skipped = doc["skipped"].toArray().size();
    return c;
}

} // namespace

class TestCliSharedData : public QObject {
    Q_OBJECT
private slots:
    void seriesAndSliceCountsArePinned_data() {
        QTest::addColumn<QString>("set");
        QTest::addColumn<QString>("series"); // sorted "kind:slices", space-separated
        QTest::addColumn<int>("skipped");
        // Counted by lucent-cli info before issue 27's changes to the reader.
        QTest::newRow("dcm_qa_ct")
            << "dcm_qa_ct"
            << "localizer:1 localizer:1 volume:113 volume:140 volume:28 volume:54" << 2;
        QTest::newRow("nema_wg04/CT1") << "nema_wg04/CT1"
                                       << "image:1 image:1" << 5;
        QTest::newRow("nema_wg04/CT2") << "nema_wg04/CT2"
                                       << "image:1 image:1" << 5;
        QTest::newRow("nema_wg04/MR1") << "nema_wg04/MR1"
                                       << "image:1 image:1" << 6;
        QTest::newRow("dcm_qa_enh")
            << "dcm_qa_enh"
            << "volume:32 volume:32 volume:6 volume:6 volume:6 volume:6" << 1;
        QTest::newRow("dcmqi_ct3slice") << "dcmqi_ct3slice"
                                        << "volume:3" << 2;
    }

    void seriesAndSliceCountsArePinned() {
        QFETCH(QString, set);
        QFETCH(QString, series);
        QFETCH(int, skipped);
        REQUIRE_DATA(set.toStdString());
        const Counts c =
            infoCounts(QString::fromStdString((test::kRealData / set.toStdString()).string()));
        QCOMPARE(c.series.join(' '), series);
        QCOMPARE(c.skipped, skipped);
    }
};

QTEST_GUILESS_MAIN(TestCliSharedData)
#include "test_cli_shared_data.moc"
