// The server's store fed by C-STORE: real CT pushed with DCMTK's storescu to
// lucent-server --dicom-listen becomes listable and openable without a
// restart, renders like the local files, and a series that grows is loaded
// anew on the next open.
#include <QJsonArray>
#include <QProcess>
#include <QStandardPaths>
#include <QTest>

#include "RemoteTestFixture.h"
#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSide = 128;

QString seriesDir() {
    return QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";
}

// Pushes files with storescu; its output when it fails.
QString push(int port, const QStringList& files) {
    QProcess storescu;
    storescu.setProcessChannelMode(QProcess::MergedChannels);
    storescu.start("storescu", QStringList{"-aet", "TESTSCU", "-aec", "LUCENT", "127.0.0.1",
                                           QString::number(port)} +
                                   files);
    if (!storescu.waitForFinished(120000) || storescu.exitCode() != 0) {
        return "storescu failed: " + QString::fromUtf8(storescu.readAll());
    }
    return {};
}

// The list's entry with this uid (empty when absent).
QJsonObject listed(RemoteTestClient& client, const QString& uid) {
    const qsizetype from = client.texts.size();
    client.send({{"type", "list"}});
    for (const QJsonValue& v : client.waitForText("series", 20000, from)["series"].toArray()) {
        if (v.toObject()["uid"].toString() == uid) {
            return v.toObject();
        }
    }
    return {};
}

// Waits until the listed series has `slices` images.
bool waitListed(RemoteTestClient& client, const QString& uid, int slices) {
    return QTest::qWaitFor(
        [&] {
            const QJsonArray dims = listed(client, uid)["dims"].toArray();
            return dims.size() == 3 && dims[2].toInt() == slices;
        },
        60000);
}

int dicomPort(const ServerProcess& server) {
    const QString out = server.startupOutput();
    const qsizetype at = out.indexOf(" on port ");
    return at < 0 ? 0 : out.mid(at + 9, out.indexOf('\n', at) - at - 9).toInt();
}

} // namespace

class TestRemoteIngest : public QObject {
    Q_OBJECT

private slots:
    void pushedSeriesIsServedAndReloadedWhenItGrows() {
        if (!QFileInfo::exists(seriesDir())) {
            QSKIP("no test data (dcm_qa_ct)");
        }
        if (QStandardPaths::findExecutable("storescu").isEmpty()) {
            QSKIP("DCMTK's storescu is not installed (packaging/install-deps.sh)");
        }
        const Catalog local = scanPath(seriesDir().toStdString());
        QCOMPARE(local.series.size(), std::size_t(1));
        const SeriesEntry& entry = local.series.front();
        const QString uid = QString::fromStdString(entry.id);
        const int slices = int(entry.slices.size());
        QVERIFY(slices > 4);
        QStringList firstHalf;
        QStringList rest;
        for (int n = 0; n < slices; ++n) {
            (n < slices / 2 ? firstHalf : rest)
                << QString::fromStdString(entry.slices[std::size_t(n)].file);
        }

        ServerProcess server("cpu", {}, {"--dicom-listen", "0", "--arrival-quiet", "0.5"});
        QVERIFY(server.port());
        const int port = dicomPort(server);
        QVERIFY2(port > 0, qPrintable(server.startupOutput()));
        RemoteTestClient client(server.port());
        QVERIFY(client.waitConnected());
        QVERIFY(client.authenticate());
        QVERIFY(listed(client, uid).isEmpty());

        // Half the series: listed with half its images, and it opens.
        const QString firstPush = push(port, firstHalf);
        QVERIFY2(firstPush.isEmpty(), qPrintable(firstPush));
        QVERIFY2(waitListed(client, uid, slices / 2), qPrintable(client.allText()));
        qsizetype from = client.texts.size();
        client.change({{"type", "open"}, {"series", uid}});
        QCOMPARE(client.waitForText("opened", 20000, from)["dims"].toArray()[2].toInt(),
                 slices / 2);
        client.change({{"type", "size"}, {"width", kSide}, {"height", kSide}});
        client.change({{"type", "tf"}, {"preset", "ct-bone"}});
        QVERIFY(client.waitForCurrentFrame());

        // The rest, while it is open: the next open loads the whole series.
        const QString secondPush = push(port, rest);
        QVERIFY2(secondPush.isEmpty(), qPrintable(secondPush));
        QVERIFY2(waitListed(client, uid, slices), qPrintable(client.allText()));
        from = client.texts.size();
        client.change({{"type", "open"}, {"series", uid}});
        QCOMPARE(client.waitForText("opened", 20000, from)["dims"].toArray()[2].toInt(), slices);
        client.change({{"type", "size"}, {"width", kSide}, {"height", kSide}});
        client.change({{"type", "tf"}, {"preset", "ct-bone"}});
        client.change({{"type", "camera"}, {"azimuth", 30}, {"elevation", 20}, {"zoom", 1.2}});
        const ReceivedFrame* frame = client.waitForCurrentFrame();
        QVERIFY2(frame, qPrintable(client.allText()));
        QCOMPARE(frame->header.format, "png");

        const Volume volume = loadSeries(entry);
        RenderDescription d;
        d.volume = &volume;
        d.width = kSide;
        d.height = kSide;
        d.transferFunction = loadPreset("ct-bone");
        d.camera = {30, 20, 1.2};
        const ImageRGBA8 reference = CpuRayCaster(volume).render(d).image;
        const double db = psnr(reference, frame->decoded());
        qInfo("pushed series: PSNR %.1f dB against the local render", db);
        QVERIFY2(db >= 40.0, qPrintable(QString("PSNR %1 dB").arg(db)));
        QVERIFY(psnr(reference, ImageRGBA8::filled(kSide, kSide, 0)) < 30.0);
        // Logs hold counts, never the patient's name.
        QVERIFY(!server.log().contains("HEAD^") && !server.log().contains("PatientName"));
    }

    void badDicomListenIsRefused() {
        QTemporaryDir dir;
        QVERIFY(writeTokenFile(dir.filePath("tokens"), "t\n"));
        QProcess process;
        process.start(QString(LUCENT_BIN_DIR) + "/lucent-server",
                      {"--store", dir.filePath("store"), "--token-file", dir.filePath("tokens"),
                       "--dicom-listen", "99999"});
        QVERIFY(process.waitForFinished(30000));
        QCOMPARE(process.exitCode(), 2);
        QVERIFY(QString::fromUtf8(process.readAllStandardError()).contains("--dicom-listen"));
    }
};

QTEST_GUILESS_MAIN(TestRemoteIngest)
#include "test_remote_ingest.moc"
