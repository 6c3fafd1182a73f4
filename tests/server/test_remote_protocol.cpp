// Protocol v1 parser and frame layout (no network).
#include <QTest>

#include "server/protocol/ProtocolMessages.h"

using namespace lucent;
using namespace lucent::remote;

namespace {

// The code of the ProtocolError the text raises, "" when it parses; fatal through `fatal`.
std::string errorCode(std::string_view text, bool* fatal = nullptr) {
    try {
        parseClientMessage(text);
    } catch (const ProtocolError& e) {
        if (fatal) {
            *fatal = e.fatal();
        }
        return e.code();
    }
    return "";
}

} // namespace

class TestRemoteProtocol : public QObject {
    Q_OBJECT

private slots:
    void parsesEveryMessage() {
        QCOMPARE(std::get<AuthRequest>(parseClientMessage(R"({"type":"auth","token":"t"})")).token,
                 "t");
        QVERIFY(std::holds_alternative<ListRequest>(parseClientMessage(R"({"type":"list"})")));
        QCOMPARE(
            std::get<OpenRequest>(parseClientMessage(R"({"type":"open","series":"1.2"})")).series,
            "1.2");
        const auto camera = std::get<CameraUpdate>(
            parseClientMessage(R"({"type":"camera","azimuth":30,"zoom":2})"));
        QCOMPARE(*camera.azimuth, 30.0);
        QVERIFY(!camera.elevation);
        QCOMPARE(*camera.zoom, 2.0);
        QCOMPARE(*std::get<TransferFunctionUpdate>(
                      parseClientMessage(R"({"type":"tf","preset":"ct-bone"})"))
                      .preset,
                 "ct-bone");
        const auto tf = std::get<TransferFunctionUpdate>(parseClientMessage(
            R"({"type":"tf","tf":{"opacity":[[0,0],[100,1]],"colour":[[0,1,0,0]]}})"));
        QCOMPARE(tf.transferFunction->opacity.size(), std::size_t(2));
        const auto mode =
            std::get<ModeUpdate>(parseClientMessage(R"({"type":"mode","mode":"iso","iso":250})"));
        QVERIFY(mode.mode == RenderMode::Isosurface);
        QCOMPARE(*mode.isoValue, 250.0);
        const auto clip = std::get<ClipUpdate>(
            parseClientMessage(R"({"type":"clip","lo":[1,2,3],"hi":[10,20,30]})"));
        QCOMPARE(clip.box.hi.y, 20.0);
        QCOMPARE(std::get<ClipUpdate>(parseClientMessage(R"({"type":"clip"})")).box.lo.x, -1e300);
        QVERIFY(std::get<QualityUpdate>(
                    parseClientMessage(R"({"type":"quality","quality":"interactive"})"))
                    .quality == Quality::Interactive);
        QCOMPARE(
            std::get<SizeUpdate>(parseClientMessage(R"({"type":"size","width":640,"height":480})"))
                .height,
            480);
        QVERIFY(std::holds_alternative<RenderRequest>(parseClientMessage(R"({"type":"render"})")));
    }

    void structuralErrorsAreFatal() {
        bool fatal = false;
        QCOMPARE(errorCode("{not json", &fatal), "malformed");
        QVERIFY(fatal);
        QCOMPARE(errorCode("[1,2]"), "malformed");
        QCOMPARE(errorCode(R"({"token":"x"})"), "malformed");
        QCOMPARE(errorCode(R"({"type":7})"), "malformed");
        fatal = false;
        QCOMPARE(errorCode(R"({"type":"reboot"})", &fatal), "unknown-type");
        QVERIFY(fatal);
        const std::string big =
            "{\"type\":\"list\",\"pad\":\"" + std::string(kMaxMessageBytes, 'x') + "\"}";
        QCOMPARE(errorCode(big, &fatal), "too-large");
        QVERIFY(fatal);
    }

    void fieldErrorsAreNotFatal() {
        const char* bad[] = {
            R"({"type":"auth"})",
            R"({"type":"auth","token":""})",
            R"({"type":"open","series":5})",
            R"({"type":"camera","azimuth":"north"})",
            R"({"type":"camera","zoom":0})",
            R"({"type":"camera","zoom":1e9})",
            R"({"type":"camera","roll":3})",
            R"({"type":"tf"})",
            R"({"type":"tf","preset":"ct-bone","tf":{}})",
            R"({"type":"tf","tf":{"opacity":[[0,2]],"colour":[[0,1,1,1]]}})",
            R"({"type":"mode","mode":"xray"})",
            R"({"type":"clip","lo":[1,2]})",
            R"({"type":"clip","lo":[5,5,5],"hi":[1,9,9]})",
            R"({"type":"quality","quality":"best"})",
            R"({"type":"size","width":8,"height":100})",
            R"({"type":"size","width":100.5,"height":100})",
            R"({"type":"size","width":100000,"height":100})",
        };
        for (const char* text : bad) {
            bool fatal = true;
            QCOMPARE(errorCode(text, &fatal), "bad-request");
            QVERIFY2(!fatal, text);
        }
    }

    void frameRoundTrip() {
        FrameHeader h;
        h.width = 320;
        h.height = 200;
        h.format = "jpeg";
        h.seq = 42;
        h.quality = Quality::Interactive;
        const std::string image("\xff\xd8 image bytes", 14);
        const std::string message = frameMessage(h, image);
        const ParsedFrame f = parseFrameMessage(message);
        QCOMPARE(f.header.width, 320);
        QCOMPARE(f.header.seq, std::uint64_t(42));
        QCOMPARE(f.header.format, "jpeg");
        QVERIFY(f.header.quality == Quality::Interactive);
        QCOMPARE(f.image, std::string_view(image));
        QVERIFY_THROWS_EXCEPTION(ProtocolError, parseFrameMessage(message.substr(0, 10)));
        QVERIFY_THROWS_EXCEPTION(ProtocolError, parseFrameMessage("\xff\xff"));
    }

    void errorReplyIsJson() {
        QCOMPARE(
            errorReply("auth-failed", "the token is not valid", true),
            R"({"code":"auth-failed","fatal":true,"message":"the token is not valid","type":"error"})");
    }
};

QTEST_GUILESS_MAIN(TestRemoteProtocol)
#include "test_remote_protocol.moc"
