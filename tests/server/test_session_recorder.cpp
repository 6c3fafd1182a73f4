// The server's recorder alone: what it keeps, its message limit, and the file
// it stores (whole, in DIR/recordings/, nothing left in DIR/tmp/), read back by
// the protocol's reader.
#include <QDir>
#include <QTemporaryDir>
#include <QTest>

#include "protocol/ProtocolMessages.h"
#include "server/RecordingStore.h"
#include "server/SessionRecorder.h"

using namespace lucent;
using namespace lucent::remote;

class TestSessionRecorder : public QObject {
    Q_OBJECT

private slots:
    void keepsRecordedMessagesWithinTheLimit() {
        QTemporaryDir store;
        RenderDescription start;
        start.width = 120;
        start.height = 80;
        start.transferFunction = loadPreset("ct-bone");
        SessionRecorder recorder(store.path().toStdString(), "1.2.3", start, nullptr);
        QVERIFY(recorder.add(QualityUpdate{Quality::Interactive})); // not kept
        QVERIFY(recorder.add(RenderRequest{}));                     // not kept
        const ClientMessage turn = parseClientMessage(R"({"type":"camera","azimuth":12.5})");
        std::size_t kept = 0;
        while (recorder.add(turn)) {
            ++kept;
            QVERIFY(kept <= kMaxRecordedMessages);
        }
        QCOMPARE(kept, kMaxRecordedMessages);
        const RecordingStopped stopped = recorder.finish("limit");
        QCOMPARE(stopped.views, int(kMaxRecordedMessages) + 1);
        QCOMPARE(stopped.reason, std::string("limit"));

        const std::string file = recordingFile(store.path().toStdString(), recorder.id());
        const Recording read = readRecording(file);
        QCOMPARE(read.header.series, std::string("1.2.3"));
        QCOMPARE(read.header.width, 120);
        QCOMPARE(read.messages.size(), kMaxRecordedMessages);
        QVERIFY(recordedStart(read).transferFunction == loadPreset("ct-bone"));
        QVERIFY(QDir(store.filePath("tmp")).isEmpty());
        const auto listed = listRecordings(store.path().toStdString());
        QCOMPARE(listed.size(), std::size_t(1));
        QCOMPARE(listed[0].id, recorder.id());
        QCOMPARE(listed[0].views, stopped.views);
    }

    // A store that cannot be written: a clear error, no file.
    void anUnwritableStoreIsAnError() {
        QTemporaryDir dir;
        QFile blocker(dir.filePath("store"));
        QVERIFY(blocker.open(QIODevice::WriteOnly)); // a file where the store's folder goes
        blocker.close();
        RenderDescription start;
        start.transferFunction = loadPreset("ct-bone");
        SessionRecorder recorder(dir.filePath("store").toStdString(), "1.2.3", start, nullptr);
        try {
            recorder.finish("stopped");
            QFAIL("a recording was stored under a file");
        } catch (const std::runtime_error& e) {
            QVERIFY2(std::string(e.what()).find("cannot write the recording") != std::string::npos,
                     e.what());
        }
    }
};

QTEST_GUILESS_MAIN(TestSessionRecorder)
#include "test_session_recorder.moc"
