// lucent-server --distributed under mpirun -n 2, started by the test on
// loopback: its frames (still, interactive, cubic after linear: the ranks read
// their parts again with a wider halo) equal the local render of the same
// volume; a teaching session's followers get the presenter's frames; a start
// that fails on rank 0 ends every rank with the reason.
#include <QJsonArray>
#include <QProcess>
#include <QTest>

#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/quality/InteractiveQuality.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/server/RemoteTestFixture.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSide = 96;

QStringList mpirun(int ranks) {
    return {LUCENT_MPIEXEC, "-n", QString::number(ranks), "--oversubscribe", "--allow-run-as-root"};
}

RenderDescription localDescription(const Volume& volume, const Camera& camera) {
    return referenceDescription(volume, camera, kSide);
}

// Authenticates (unless told not to), opens the only series at kSide with ct-bone; its uid.
QString openView(RemoteTestClient& client, bool authenticate = true) {
    if (authenticate && (!client.waitConnected() || !client.authenticate())) {
        return {};
    }
    return openOnlySeries(client, kSide);
}

double psnrTo(const RenderDescription& d, const ReceivedFrame& frame, const QString& name) {
    CpuRayCaster cpu(*d.volume);
    const ImageRGBA8 local = cpu.render(d).image;
    const ImageRGBA8 remote = frame.decoded();
    const double db = remote.width == local.width ? psnr(local, remote) : 0.0;
    qInfo("%s: %.1f dB, render %.1f ms", qPrintable(name), db, frame.header.renderMs);
    if (db < 40.0) {
        QImage(remote.pixels.data(), remote.width, remote.height, QImage::Format_RGBA8888)
            .save(QDir::temp().filePath("distributed_server_" + name + ".png"));
    }
    return db;
}

} // namespace

class TestDistributedServer : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        if (QString(LUCENT_MPIEXEC).isEmpty()) {
            QFAIL("mpiexec was not found when this test was configured: install openmpi-bin "
                  "(packaging/install-deps.sh)");
        }
    }

    void framesEqualTheLocalRender_data() {
        QTest::addColumn<QString>("backend");
        QTest::newRow("cpu") << "cpu";
        QTest::newRow("gl") << "gl"; // llvmpipe here: each rank its own EGL context
    }
    void framesEqualTheLocalRender() {
        QFETCH(QString, backend);
        ServerProcess server(backend, {}, {"--distributed"}, ServerProcess::Start::Now, mpirun(2));
        QVERIFY(server.port());
        RemoteTestClient client(server.port(), {"lucent.v2"});
        QVERIFY(!openView(client).isEmpty());
        QVERIFY(client.texts.size() > 0);
        QVERIFY2(client.waitForText("hello")["backend"].toString().contains("distributed: 2 ranks"),
                 qPrintable(client.allText()));
        const Volume volume = loadPath(server.volumeFile().toStdString());

        // A still frame from an oblique view.
        client.change({{"type", "camera"}, {"azimuth", 35}, {"elevation", 15}, {"zoom", 1.3}});
        const ReceivedFrame* still = client.waitForCurrentFrame();
        QVERIFY2(still, qPrintable(client.allText() + server.log()));
        QCOMPARE(still->header.format, "png");
        RenderDescription d = localDescription(volume, {35, 15, 1.3});
        QVERIFY(psnrTo(d, *still, backend + "_still") >= 40.0);
        // Not a blank image.
        QVERIFY(psnr(frameOf(*still), ImageRGBA8::filled(kSide, kSide, 0)) < 30.0);

        // An interactive frame: half the size, twice the step, JPEG.
        client.change({{"type", "quality"}, {"quality", "interactive"}});
        client.change({{"type", "camera"}, {"azimuth", -50}});
        const ReceivedFrame* moving = client.waitForCurrentFrame();
        // The camera keeps the elevation and zoom it was given before.
        QVERIFY2(moving, qPrintable(client.allText()));
        QCOMPARE(moving->header.format, "jpeg");
        const RenderDescription di =
            interactiveDescription(localDescription(volume, {-50, 15, 1.3, 30}));
        QVERIFY(psnrTo(di, *moving, backend + "_interactive") >= 32.0);

        // Cubic after linear frames: the parts are read again with the
        // tricubic halo; the frame still equals the whole volume's.
        client.change({{"type", "quality"}, {"quality", "still"}});
        client.change({{"type", "sampling"}, {"interp", "cubic"}, {"step", 0.4}});
        const ReceivedFrame* cubic = client.waitForCurrentFrame();
        QVERIFY2(cubic, qPrintable(client.allText() + server.log()));
        d = localDescription(volume, {-50, 15, 1.3, 30});
        d.sampling.interpolation = Interpolation::Cubic;
        d.sampling.step = 0.4;
        QVERIFY(psnrTo(d, *cubic, backend + "_cubic") >= 40.0);
    }

    // A teaching session on the distributed server: the presenter turns the
    // volume, both followers receive the same frame bytes.
    void teachingSessionFollowersWatch() {
        ServerProcess server("cpu", {}, {"--distributed"}, ServerProcess::Start::Now, mpirun(2));
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port());
        QVERIFY(presenter.waitConnected() && presenter.authenticate());
        presenter.send({{"type", "session-create"}});
        const QString session = presenter.waitForText("session-created")["session"].toString();
        QVERIFY(!session.isEmpty());
        QVERIFY(!openView(presenter, false).isEmpty());
        if (!presenter.waitForCurrentFrame()) {
            QFAIL(qPrintable(presenter.allText().right(600)));
        }

        std::vector<std::unique_ptr<RemoteTestClient>> followers;
        for (int n = 0; n < 2; ++n) {
            followers.push_back(std::make_unique<RemoteTestClient>(server.port()));
            RemoteTestClient& f = *followers.back();
            QVERIFY(f.waitConnected() && f.authenticate());
            f.send({{"type", "session-join"}, {"session", session}});
            QCOMPARE(f.waitForText("session-state")["role"].toString(), "follower");
            QVERIFY(!f.waitForText("opened").isEmpty());
        }
        presenter.change({{"type", "camera"}, {"azimuth", 120}, {"elevation", -20}});
        const ReceivedFrame* mine = presenter.waitForCurrentFrame();
        QVERIFY2(mine, qPrintable(presenter.allText()));
        for (const auto& f : followers) {
            QVERIFY(QTest::qWaitFor(
                [&] {
                    return !f->frames.isEmpty() && f->frames.back().header.seq == presenter.seq;
                },
                60000));
            QCOMPARE(f->frames.back().image, mine->image);
        }
        const Volume volume = loadPath(server.volumeFile().toStdString());
        QVERIFY(psnrTo(localDescription(volume, {120, -20, 1, 30}), *mine, "session") >= 40.0);
    }

    // Rank 0 cannot start (its token file is missing): every rank ends, the
    // job's status says so and rank 0 names the file. --check ends them all
    // with success.
    void aFailedStartEndsEveryRank() {
        const QTemporaryDir dir;
        QProcess job;
        job.setProcessChannelMode(QProcess::SeparateChannels);
        const QStringList launch = mpirun(2);
        const QString server = QString(LUCENT_BIN_DIR) + "/lucent-server";
        const QStringList common = {
            "--store",       dir.filePath("store"), "--data", dir.filePath("none"),
            "--distributed", "--backend",           "cpu"};
        job.start(launch.front(), launch.mid(1) +
                                      QStringList{server, "--token-file", dir.filePath("missing")} +
                                      common);
        QVERIFY(job.waitForFinished(60000));
        QVERIFY(job.exitCode() != 0);
        const QString err = QString::fromUtf8(job.readAllStandardError());
        QVERIFY2(err.contains("missing") && err.contains("token file"), qPrintable(err));

        QVERIFY(writeTokenFile(dir.filePath("tokens"), "t0ken\n"));
        writeMetaImage(syntheticCt(), dir.filePath("none").toStdString() + ".mhd");
        QStringList check = common;
        check[3] = dir.filePath("none.mhd");
        job.start(launch.front(),
                  launch.mid(1) +
                      QStringList{server, "--token-file", dir.filePath("tokens"), "--check"} +
                      check);
        QVERIFY(job.waitForFinished(60000));
        QVERIFY2(job.exitCode() == 0, qPrintable(job.readAllStandardError()));
        QVERIFY(QString::fromUtf8(job.readAllStandardOutput()).contains("1 series"));
    }

private:
    static ImageRGBA8 frameOf(const ReceivedFrame& f) { return f.decoded(); }
};

QTEST_GUILESS_MAIN(TestDistributedServer)
#include "test_distributed_server.moc"
