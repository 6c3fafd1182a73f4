// Recording and replay in the protocol (version 4): the messages' refusals and
// versions, and the recording file (protocol/Recording.h) written and read back,
// with the reader's errors naming the file and the line. No network.
#include <QTest>

#include <QDir>

#include <cstdio>
#include <fstream>

#include "protocol/ProtocolMessages.h"

using namespace lucent;
using namespace lucent::remote;

namespace {

// The code and message of the ProtocolError the text raises ("" when it parses).
std::pair<std::string, std::string> refusal(std::string_view text, int version = kProtocolVersion) {
    try {
        parseClientMessage(text, version);
    } catch (const ProtocolError& e) {
        return {e.code(), e.what()};
    }
    return {};
}

// A small recording as the server writes it: the start view, a drag, a preset, a mode.
std::string sampleRecording(int views = 4) {
    RenderDescription start;
    start.width = 96;
    start.height = 64;
    start.transferFunction = loadPreset("ct-bone");
    RecordingHeader header;
    header.series = "1.3.12.2";
    header.width = 96;
    header.height = 64;
    header.createdMs = 1790000000000;
    header.durationMs = 900;
    header.views = views;
    std::string text = recordingHeaderLine(header) + "\n";
    for (const ClientMessage& m : viewMessages(start)) {
        text += recordingStartLine(m) + "\n";
    }
    CameraUpdate turn;
    turn.values.push_back(checkedOptionValue("camera", *findWireOption("camera", "azimuth"), "30"));
    text += recordedMessageLine(100, InteractionUpdate{true}) + "\n";
    text += recordedMessageLine(120, turn) + "\n";
    text += recordedMessageLine(300, InteractionUpdate{false}) + "\n";
    text += recordedMessageLine(500, TransferFunctionUpdate{"ct-soft-tissue", std::nullopt}) + "\n";
    text += recordedMessageLine(900, parseClientMessage(R"({"type":"mode","mode":"mip"})")) + "\n";
    return text;
}

std::string readError(const std::string& text) {
    try {
        parseRecording(text, "rec.jsonl");
    } catch (const RecordingError& e) {
        return e.what();
    }
    return "";
}

// `text` with line `n` (1-based) replaced.
std::string withLine(const std::string& text, int n, const std::string& line) {
    std::string out;
    int at = 1;
    std::size_t begin = 0;
    while (begin < text.size()) {
        const std::size_t end = text.find('\n', begin);
        out += (at == n ? line : text.substr(begin, end - begin)) + "\n";
        begin = end + 1;
        ++at;
    }
    return out;
}

} // namespace

class TestRecordingProtocol : public QObject {
    Q_OBJECT

private slots:
    void messagesAreVersionFour() {
        for (const char* text :
             {R"({"type":"record","state":"start"})", R"({"type":"recording-list"})",
              R"({"type":"replay","recording":"abc"})", R"({"type":"replay-step"})",
              R"({"type":"replay-stop"})"}) {
            QCOMPARE(refusal(text).first, std::string());
            const auto [code, message] = refusal(text, 3);
            QCOMPARE(code, std::string("unknown-type"));
            QVERIFY2(message.find("version 4") != std::string::npos, message.c_str());
        }
        QCOMPARE(std::get<ReplayRequest>(parseClientMessage(R"({"type":"replay","recording":"a"})"))
                     .pace,
                 ReplayPace::Original);
    }

    void refusalsNameTheMessageAndKey_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("names");
        QTest::newRow("record without state") << R"({"type":"record"})"
                                              << "record: 'state'";
        QTest::newRow("record pause") << R"({"type":"record","state":"pause"})"
                                      << "record: 'state'";
        QTest::newRow("record extra") << R"({"type":"record","state":"stop","id":1})"
                                      << "record: unknown field 'id'";
        QTest::newRow("replay without id") << R"({"type":"replay"})"
                                           << "replay: 'recording'";
        QTest::newRow("replay path") << R"({"type":"replay","recording":"../../etc/passwd"})"
                                     << "replay: 'recording'";
        QTest::newRow("replay long")
            << QString(R"({"type":"replay","recording":"%1"})").arg(QString(65, 'a'))
            << "replay: 'recording'";
        QTest::newRow("replay pace") << R"({"type":"replay","recording":"a","pace":"fast"})"
                                     << "replay: 'pace'";
        QTest::newRow("replay pace type") << R"({"type":"replay","recording":"a","pace":2})"
                                          << "replay: 'pace'";
        QTest::newRow("step extra") << R"({"type":"replay-step","n":2})"
                                    << "replay-step: unknown field 'n'";
        QTest::newRow("list extra") << R"({"type":"recording-list","all":true})"
                                    << "recording-list: unknown field 'all'";
    }

    void refusalsNameTheMessageAndKey() {
        QFETCH(QString, text);
        QFETCH(QString, names);
        const auto [code, message] = refusal(text.toStdString());
        QCOMPARE(code, std::string("bad-request"));
        QVERIFY2(message.find(names.toStdString()) != std::string::npos, message.c_str());
    }

    void recordingRoundTrips() {
        const Recording r = parseRecording(sampleRecording(), "rec.jsonl");
        QCOMPARE(r.header.series, std::string("1.3.12.2"));
        QCOMPARE(r.header.views, 4);
        QCOMPARE(r.start.size(), std::size_t(6));
        QCOMPARE(r.messages.size(), std::size_t(5));
        const std::vector<RenderDescription> views = recordedViews(r);
        QCOMPARE(views.size(), std::size_t(4));
        QCOMPARE(views[0].width, 96);
        QCOMPARE(views[0].camera.azimuth, 0.0);
        QCOMPARE(views[1].camera.azimuth, 30.0);
        QVERIFY(views[2].transferFunction == loadPreset("ct-soft-tissue"));
        QCOMPARE(views[3].mode, RenderMode::Mip);
        // The view at a time: the messages up to it.
        QCOMPARE(recordedViewAt(r, 119).camera.azimuth, 0.0);
        QCOMPARE(recordedViewAt(r, 120).camera.azimuth, 30.0);
        QCOMPARE(recordedViewAt(r, 899).mode, RenderMode::Dvr);
        QCOMPARE(recordedViewAt(r, 900).mode, RenderMode::Mip);
        // From a file too.
        const std::string file = QDir::temp().filePath("lucent-test-rec.jsonl").toStdString();
        std::ofstream(file, std::ios::binary) << sampleRecording();
        QCOMPARE(readRecording(file).messages.size(), std::size_t(5));
        QCOMPARE(readRecordingHeader(file).durationMs, std::int64_t(900));
        std::remove(file.c_str());
    }

    void readerErrorsNameFileAndLine_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("error");
        const std::string good = sampleRecording();
        QTest::newRow("empty") << ""
                               << "rec.jsonl:0: empty";
        QTest::newRow("not a recording") << R"({"type":"camera"})"
                                         << "rec.jsonl:1: unknown field 'type'";
        QTest::newRow("format")
            << QString::fromStdString(withLine(
                   good, 1,
                   R"({"lucent_recording":2,"series":"1","width":96,"height":64,"created":0,"duration_ms":900,"views":4})"))
            << "rec.jsonl:1: recording format 2";
        QTest::newRow("no series")
            << QString::fromStdString(withLine(
                   good, 1,
                   R"({"lucent_recording":1,"width":96,"height":64,"created":0,"duration_ms":900,"views":4})"))
            << "rec.jsonl:1: 'series'";
        QTest::newRow("not json") << QString::fromStdString(withLine(good, 3, "{\"start\":"))
                                  << "rec.jsonl:3: not a JSON object";
        QTest::newRow("refused message")
            << QString::fromStdString(
                   withLine(good, 9, R"({"at_ms":120,"message":{"type":"camera","zoom":500}})"))
            << "rec.jsonl:9: camera: 'zoom'";
        QTest::newRow("not kept") << QString::fromStdString(withLine(
                                         good, 9,
                                         R"({"at_ms":120,"message":{"type":"open","series":"1"}})"))
                                  << "rec.jsonl:9: 'open' is not a message recordings keep";
        QTest::newRow("back in time")
            << QString::fromStdString(withLine(
                   good, 10, R"({"at_ms":50,"message":{"type":"interaction","state":"end"}})"))
            << "rec.jsonl:10: 'at_ms' goes back in time";
        QTest::newRow("past the end")
            << QString::fromStdString(withLine(
                   good, 10, R"({"at_ms":901,"message":{"type":"interaction","state":"end"}})"))
            << "rec.jsonl:10: 'at_ms' must be an integer from 0 to 900";
        QTest::newRow("cut short")
            << QString::fromStdString(good.substr(0, good.rfind('\n', good.size() - 2) + 1))
            << "the header counts 4 views, the lines hold 3 (cut short?)";
        QTest::newRow("views") << QString::fromStdString(sampleRecording(7))
                               << "the header counts 7 views, the lines hold 4";
        QTest::newRow("no start") << QString::fromStdString(good.substr(0, good.find('\n') + 1))
                                  << "no start view";
        QTest::newRow("start after")
            << QString::fromStdString(good + R"({"start":{"type":"camera"}})")
            << "a start line after the recorded messages";
        QTest::newRow("blank line") << QString::fromStdString(good + "\n") << "an empty line";
    }

    void readerErrorsNameFileAndLine() {
        QFETCH(QString, text);
        QFETCH(QString, error);
        const std::string message = readError(text.toStdString());
        QVERIFY2(message.find(error.toStdString()) != std::string::npos,
                 ("got '" + message + "'").c_str());
        QVERIFY2(message.starts_with("rec.jsonl:"), message.c_str());
    }

    void missingFileIsAnError() {
        try {
            readRecording("/nonexistent/rec.jsonl");
            QFAIL("a missing file read");
        } catch (const RecordingError& e) {
            QVERIFY2(std::string(e.what()).find("/nonexistent/rec.jsonl") != std::string::npos,
                     e.what());
        }
    }

    // The one list of what a recording keeps, and what a stepped replay steps by.
    void recordedMessages() {
        QVERIFY(isRecordedMessage(CameraUpdate{}));
        QVERIFY(isRecordedMessage(InteractionUpdate{true}));
        QVERIFY(!isRecordedMessage(QualityUpdate{}));
        QVERIFY(!isRecordedMessage(RenderRequest{}));
        QVERIFY(!isRecordedMessage(OpenRequest{"1"}));
        QVERIFY(showsRecordedView(SizeUpdate{64, 64}));
        QVERIFY(!showsRecordedView(InteractionUpdate{false}));
        QVERIFY(isRecordingControl(ReplayStep{}));
        QVERIFY(!isRecordingControl(CameraUpdate{}));
    }
};

QTEST_GUILESS_MAIN(TestRecordingProtocol)
#include "test_recording_protocol.moc"
