// lucent-cli hang on a real CT and a prior of it made by DCMTK (dcmodify: new study and
// series UIDs, an earlier study date, new instance UIDs): the protocol that wins, which
// series goes where, a forced protocol, the user's folder, errors naming file and key.
#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>

#include "tests/support/CliRunner.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

const QString kPriorStudy = "1.2.826.0.1.3680043.9.7433.28.1";
const QString kPriorSeries = "1.2.826.0.1.3680043.9.7433.28.2";

const QJsonObject json(const test::CliRun& run) {
    return QJsonDocument::fromJson(run.out.toUtf8()).object();
}

// The series of the viewport of `slot` in the result.
QJsonObject seriesIn(const QJsonObject& root, const QString& slot) {
    for (const QJsonValue& v : root["result"]["viewports"].toArray()) {
        if (v["slot"].toString() == slot) {
            return v["series"].toObject();
        }
    }
    return {};
}

// A user's protocol with a bad regex, and one that beats every shipped one.
const char* kBadProtocol =
    "{\"name\": \"Bad\", \"series\": [{\"name\": \"a\", \"description\": \"T1[\"}], "
    "\"viewportSets\": [{\"layout\": \"1x1\", \"viewports\": [{\"series\": \"a\"}]}]}";
const char* kOneUp =
    "{\"name\": \"One up\", \"priority\": 100, \"series\": [{\"name\": \"a\", "
    "\"kind\": \"volume\", \"mustMatch\": [\"kind\"]}], \"viewportSets\": [{\"layout\": "
    "\"1x1\", \"viewports\": [{\"series\": \"a\", \"view\": \"sagittal\"}]}]}";

} // namespace

class TestHangCli : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    QString current_, prior_, originalUid_;

private slots:
    void initTestCase() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        const QString dcmodify = QStandardPaths::findExecutable("dcmodify");
        if (dcmodify.isEmpty()) {
            QSKIP("dcmodify (DCMTK) not found");
        }
        // The children's data home: no user protocols but this test's.
        qputenv("XDG_DATA_HOME", dir_.filePath("data").toUtf8());
        const QDir source(
            QString::fromStdString((test::kRealData / "dcm_qa_ct/Philips_S21570/S2010").string()));
        current_ = dir_.filePath("current");
        prior_ = dir_.filePath("prior");
        QStringList priorFiles;
        for (const QString& folder : {current_, prior_}) {
            QVERIFY(QDir().mkpath(folder));
            for (const QString& name : source.entryList(QDir::Files)) {
                QVERIFY(QFile::copy(source.filePath(name), folder + "/" + name));
                if (folder == prior_) {
                    priorFiles << folder + "/" + name;
                }
            }
        }
        const test::CliRun edit = test::runProgram(
            dcmodify,
            QStringList{"-nb", "-gin", "-m", "(0020,000d)=" + kPriorStudy, "-m",
                        "(0020,000e)=" + kPriorSeries, "-m", "(0008,0020)=20140206"} +
                priorFiles,
            60000);
        QVERIFY2(edit.exitCode == 0, qPrintable(edit.err));
        const test::CliRun info = test::runCli({"info", current_, "--json"});
        originalUid_ = json(info)["series"][0]["uid"].toString();
        QVERIFY(!originalUid_.isEmpty());
    }

    void ctHeadHangsCurrentBesidePrior() {
        const test::CliRun run = test::runCli({"hang", prior_, current_, "--json"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const QJsonObject root = json(run);
        QCOMPARE(root["result"]["protocol"].toString(), QString("CT head: brain and bone"));
        QCOMPARE(root["ranking"][0]["protocol"].toString(), QString("CT head: brain and bone"));
        QCOMPARE(root["result"]["rows"].toInt(), 1);
        QCOMPARE(root["result"]["columns"].toInt(), 2);
        const QJsonObject brain = seriesIn(root, "brain");
        QCOMPARE(brain["uid"].toString(), originalUid_);
        QCOMPARE(brain["study_date"].toString(), QString("20150206"));
        QCOMPARE(brain["study_order"].toInt(), 0);
        QVERIFY(root["result"]["missing_study_orders"].toArray().isEmpty());
        // The second set: the prior beside the current one, one link group.
        const QJsonObject set1 =
            json(test::runCli({"hang", prior_, current_, "--json", "--set", "1"}));
        const QJsonObject prior = seriesIn(set1, "prior");
        QCOMPARE(prior["uid"].toString(), kPriorSeries);
        QCOMPARE(prior["study_uid"].toString(), kPriorStudy);
        QCOMPARE(prior["study_date"].toString(), QString("20140206"));
        QCOMPARE(prior["study_order"].toInt(), 1);
        QCOMPARE(prior["path"].toString(), prior_);
        const QJsonArray viewports = set1["result"]["viewports"].toArray();
        QCOMPARE(viewports[0]["link"].toInt(), viewports[1]["link"].toInt());
        QCOMPARE(viewports[1]["window"].toString(), QString("Brain"));
        // The same in words.
        const test::CliRun text = test::runCli({"hang", current_, prior_, "--set", "1"});
        QVERIFY2(text.exitCode == 0, qPrintable(text.err));
        QVERIFY2(text.out.contains("protocol: CT head: brain and bone  score 16"),
                 qPrintable(text.out));
        QVERIFY2(text.out.contains(QRegularExpression("\\[0,1\\] prior +axial +Brain +" +
                                                      QRegularExpression::escape(kPriorSeries) +
                                                      "  20140206 \\(prior 1\\)")),
                 qPrintable(text.out));
    }

    void currentAloneAsksForThePrior() {
        const QJsonObject root = json(test::runCli({"hang", current_, "--json"}));
        QCOMPARE(root["result"]["protocol"].toString(), QString("CT head: brain and bone"));
        QCOMPARE(root["result"]["missing_study_orders"].toArray(), QJsonArray{1});
        // The generic compare needs its prior: not applicable once all priors are there.
        for (const QJsonValue& r : root["ranking"].toArray()) {
            if (r["protocol"].toString() == "Current vs prior") {
                QVERIFY(!r["applicable"].toBool());
            }
        }
        // Before the priors lookup it applies (and asks for prior 1).
        const QJsonObject pending =
            json(test::runCli({"hang", current_, "--json", "--priors-pending"}));
        QCOMPARE(pending["ranking"][1]["protocol"].toString(), QString("Current vs prior"));
        QVERIFY(pending["ranking"][1]["applicable"].toBool());
    }

    void forcedProtocol() {
        const QJsonObject root =
            json(test::runCli({"hang", current_, prior_, "--json", "--protocol", "mpr-2x2"}));
        QCOMPARE(root["result"]["protocol"].toString(), QString("MPR 2x2"));
        const QJsonArray viewports = root["result"]["viewports"].toArray();
        QCOMPARE(viewports.size(), 4);
        QStringList views;
        for (const QJsonValue& v : viewports) {
            QCOMPARE(v["series"]["uid"].toString(), originalUid_);
            views << v["view"].toString();
        }
        QCOMPARE(views, (QStringList{"axial", "3d", "coronal", "sagittal"}));
        const test::CliRun unknown = test::runCli({"hang", current_, "--protocol", "nope"});
        QCOMPARE(unknown.exitCode, 2);
        QVERIFY2(unknown.err.contains("no protocol 'nope'; the protocols are: "),
                 qPrintable(unknown.err));
    }

    void userFolderFirstAndItsErrorsNamed() {
        const QString user = dir_.filePath("mine");
        QVERIFY(QDir().mkpath(user));
        QFile bad(user + "/bad.json");
        QVERIFY(bad.open(QIODevice::WriteOnly));
        bad.write(kBadProtocol);
        bad.close();
        QFile good(user + "/one.json");
        QVERIFY(good.open(QIODevice::WriteOnly));
        good.write(kOneUp);
        good.close();
        const test::CliRun run = test::runCli({"hang", current_, "--protocols", user, "--json"});
        QCOMPARE(run.exitCode, 3);
        QVERIFY2(run.err.contains(user + "/bad.json: series[0].description: bad regular "
                                         "expression 'T1['"),
                 qPrintable(run.err));
        const QJsonObject root = json(run);
        QCOMPARE(root["result"]["protocol"].toString(), QString("One up"));
        QCOMPARE(root["errors"].toArray().size(), 1);
        // Without the flag the data home's lucent/hanging is read.
        QVERIFY(QDir().mkpath(dir_.filePath("data/lucent/hanging")));
        QVERIFY(QFile::copy(user + "/one.json", dir_.filePath("data/lucent/hanging/one.json")));
        const test::CliRun home = test::runCli({"hang", current_, "--json"});
        QCOMPARE(home.exitCode, 0);
        QCOMPARE(json(home)["result"]["protocol"].toString(), QString("One up"));
    }

    void usageAndNothingLoadable() {
        QCOMPARE(test::runCli({"hang"}).exitCode, 2);
        const QString empty = dir_.filePath("empty");
        QVERIFY(QDir().mkpath(empty));
        QCOMPARE(test::runCli({"hang", empty}).exitCode, 3);
    }
};

QTEST_GUILESS_MAIN(TestHangCli)
#include "test_hang_cli.moc"
