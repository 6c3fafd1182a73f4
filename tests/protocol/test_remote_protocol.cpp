// Protocol v1 parser and frame layout (no network).
#include <QTest>

#include <QImage>

#include <random>

#include "protocol/AdaptiveQuality.h"
#include "protocol/PngEncoder.h"
#include "protocol/ProtocolMessages.h"

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
        QVERIFY(!camera.distance && !camera.panRight && !camera.panUp); // optional: old clients
        const auto panned = std::get<CameraUpdate>(
            parseClientMessage(R"({"type":"camera","distance":350,"pan_right":-12.5,"pan_up":4})"));
        QCOMPARE(*panned.distance, 350.0);
        QCOMPARE(*panned.panRight, -12.5);
        QCOMPARE(*panned.panUp, 4.0);
        QVERIFY(!panned.azimuth);
        QCOMPARE(*std::get<CameraUpdate>(parseClientMessage(R"({"type":"camera","distance":0})"))
                      .distance,
                 0.0); // 0: fit the volume
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

    void parsesInteractionAndSessionMessages() {
        QVERIFY(std::get<InteractionUpdate>(
                    parseClientMessage(R"({"type":"interaction","state":"start"})"))
                    .active);
        QVERIFY(!std::get<InteractionUpdate>(
                     parseClientMessage(R"({"type":"interaction","state":"end"})"))
                     .active);
        QVERIFY(isViewMessage(parseClientMessage(R"({"type":"interaction","state":"end"})")));
        QVERIFY(std::holds_alternative<SessionCreate>(
            parseClientMessage(R"({"type":"session-create"})")));
        QCOMPARE(
            std::get<SessionJoin>(parseClientMessage(R"({"type":"session-join","session":"ab12"})"))
                .session,
            "ab12");
        QCOMPARE(
            std::get<SessionHandover>(parseClientMessage(R"({"type":"session-handover","to":7})"))
                .to,
            std::uint64_t(7));
        QVERIFY(std::holds_alternative<SessionLeave>(
            parseClientMessage(R"({"type":"session-leave"})")));
        QVERIFY(!isViewMessage(parseClientMessage(R"({"type":"session-leave"})")));
        QVERIFY(!isViewMessage(parseClientMessage(R"({"type":"list"})")));
        const char* bad[] = {
            R"({"type":"interaction"})",
            R"({"type":"interaction","state":"drag"})",
            R"({"type":"session-create","name":"x"})",
            R"({"type":"session-join"})",
            R"({"type":"session-join","session":5})",
            R"({"type":"session-handover","to":"me"})",
            R"({"type":"session-handover","to":-3})",
            R"({"type":"session-handover","to":0})",
            R"({"type":"session-leave","now":true})",
        };
        for (const char* text : bad) {
            bool fatal = true;
            QCOMPARE(errorCode(text, &fatal), "bad-request");
            QVERIFY2(!fatal, text);
        }
        const std::string longId =
            "{\"type\":\"session-join\",\"session\":\"" + std::string(100, 'a') + "\"}";
        QCOMPARE(errorCode(longId), "bad-request");
    }

    void adaptiveQualityHoldsTheFrameRate() {
        AdaptiveQuality adaptive; // 50 ms a frame
        const InteractiveSetting start = adaptive.current();
        QCOMPARE(start.scale, 0.5);
        // Slow frames step down to the cheapest setting and stay there.
        for (int n = 0; n < 20; ++n) {
            adaptive.record(200.0);
        }
        QCOMPARE(adaptive.level(), kInteractiveLevels - 1);
        QCOMPARE(adaptive.current().scale, 0.35);
        QCOMPARE(adaptive.current().jpegQuality, 60);
        // Fast frames climb back to full size, JPEG quality 85.
        for (int n = 0; n < 40; ++n) {
            adaptive.record(5.0);
        }
        QCOMPARE(adaptive.level(), std::size_t(0));
        QCOMPARE(adaptive.current().scale, 1.0);
        QCOMPARE(adaptive.current().jpegQuality, 85);
        // Frames that cost what they may (between 45 % and 100 % of the
        // target) leave the setting alone.
        AdaptiveQuality steady;
        for (int n = 0; n < 20; ++n) {
            steady.record(40.0);
        }
        QCOMPARE(steady.level(), std::size_t(4));
        // A cost model: each level's frame costs its pixels; 100 ms at full
        // size settles on the best level under 50 ms.
        AdaptiveQuality modelled;
        for (int n = 0; n < 40; ++n) {
            const InteractiveSetting s = modelled.current();
            modelled.record(100.0 * s.scale * s.scale);
        }
        QCOMPARE(modelled.current().scale, 0.5);
        for (const InteractiveSetting& s : kInteractiveLadder) {
            QVERIFY(s.jpegQuality >= 50 && s.jpegQuality <= 85);
        }
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
            R"({"type":"camera","distance":-1})",
            R"({"type":"camera","distance":1e6})",
            R"({"type":"camera","pan_right":"left"})",
            R"({"type":"camera","pan_up":-2e5})",
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
        QCOMPARE(f.header.scale, 1.0);
        h.scale = 0.35;
        h.jpegQuality = 55;
        const ParsedFrame g = parseFrameMessage(frameMessage(h, image));
        QCOMPARE(g.header.scale, 0.35);
        QCOMPARE(g.header.jpegQuality, 55);
        QVERIFY_THROWS_EXCEPTION(ProtocolError, parseFrameMessage(message.substr(0, 10)));
        QVERIFY_THROWS_EXCEPTION(ProtocolError, parseFrameMessage("\xff\xff"));
    }

    void pngEncoderIsLossless() {
        std::mt19937 random(7);
        for (const auto& [w, h] : {std::pair{1, 1}, {17, 5}, {256, 193}}) {
            std::vector<std::uint8_t> rgba(std::size_t(w) * h * 4);
            for (int y = 0; y < h; ++y) {
                for (int x = 0; x < w; ++x) {
                    std::uint8_t* p = &rgba[(std::size_t(y) * w + x) * 4];
                    const bool dark = (x / 8 + y / 8) % 2 == 0; // runs and noise
                    p[0] = dark ? 0 : std::uint8_t(random());
                    p[1] = dark ? 0 : std::uint8_t(x * 3 + y);
                    p[2] = dark ? 0 : std::uint8_t(200 - y);
                    p[3] = 255;
                }
            }
            const std::string png = encodePng(rgba, w, h);
            const QImage decoded =
                QImage::fromData(QByteArray(png.data(), qsizetype(png.size())), "PNG")
                    .convertToFormat(QImage::Format_RGBA8888);
            QCOMPARE(decoded.width(), w);
            QCOMPARE(decoded.height(), h);
            for (int y = 0; y < h; ++y) {
                QVERIFY(std::equal(rgba.begin() + std::ptrdiff_t(y) * w * 4,
                                   rgba.begin() + std::ptrdiff_t(y + 1) * w * 4,
                                   decoded.constScanLine(y)));
            }
        }
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, encodePng({}, 2, 2));
    }

    void errorReplyIsJson() {
        QCOMPARE(
            errorReply("auth-failed", "the token is not valid", true),
            R"({"code":"auth-failed","fatal":true,"message":"the token is not valid","type":"error"})");
    }
};

QTEST_GUILESS_MAIN(TestRemoteProtocol)
#include "test_remote_protocol.moc"
