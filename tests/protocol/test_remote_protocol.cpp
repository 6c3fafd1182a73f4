// The protocol's messages: one writer and one reader each way, the options table
// behind camera, mode and sampling, versions, the frame layout (no network).
#include <QTest>

#include <QImage>
#include <QJsonDocument>
#include <QJsonObject>

#include <fstream>
#include <iterator>
#include <random>
#include <set>

#include "protocol/AdaptiveQuality.h"
#include "protocol/PngEncoder.h"
#include "protocol/ProtocolMessages.h"

using namespace lucent;
using namespace lucent::remote;

namespace {

// The code of the ProtocolError the text raises, "" when it parses; fatal and the
// message through `fatal` and `message`.
std::string errorCode(std::string_view text, bool* fatal = nullptr, int version = kProtocolVersion,
                      std::string* message = nullptr) {
    try {
        parseClientMessage(text, version);
    } catch (const ProtocolError& e) {
        if (fatal) {
            *fatal = e.fatal();
        }
        if (message) {
            *message = e.what();
        }
        return e.code();
    }
    return "";
}

// A description with every wire-carried setting away from its default.
RenderDescription unusualDescription() {
    RenderDescription d;
    d.width = 640;
    d.height = 360;
    d.transferFunction = loadPreset("mr-default");
    d.mode = RenderMode::Isosurface;
    d.isoValue = 250.5;
    d.clip.lo = {1.0, 2.5, 3.0};
    d.clip.hi = {100.0, 200.0, 30.25};
    d.camera.azimuth = 33.3;
    d.camera.elevation = -12.25;
    d.camera.zoom = 1.75;
    d.camera.distance = 420.5;
    d.camera.panRight = -7.125;
    d.camera.panUp = 3.0;
    d.sampling.step = 0.3;
    d.sampling.interpolation = Interpolation::Cubic;
    d.sampling.classification = Classification::Pre;
    d.sampling.preintegrate = true;
    d.transferFunction.shading.enabled = false;
    d.sampling.emptySpaceLeaping = false;
    d.sampling.precision = Precision::Double;
    d.sampling.earlyTermination = 0.95;
    d.sampling.brickSize = 32; // not on the wire
    return d;
}

QStringList keysOf(const std::string& json) {
    QStringList keys = QJsonDocument::fromJson(QByteArray::fromStdString(json)).object().keys();
    keys.sort();
    return keys;
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
        QCOMPARE(*camera.number("azimuth"), 30.0);
        QVERIFY(!camera.number("elevation"));
        QCOMPARE(*camera.number("zoom"), 2.0);
        QVERIFY(!camera.text("distance") && !camera.text("pan_right") &&
                !camera.text("pan_up")); // optional: old clients
        const auto panned = std::get<CameraUpdate>(
            parseClientMessage(R"({"type":"camera","distance":350,"pan_right":-12.5,"pan_up":4})"));
        QCOMPARE(*panned.number("distance"), 350.0);
        QCOMPARE(*panned.number("pan_right"), -12.5);
        QCOMPARE(*panned.number("pan_up"), 4.0);
        QVERIFY(!panned.text("azimuth"));
        QCOMPARE(*std::get<CameraUpdate>(parseClientMessage(R"({"type":"camera","distance":0})"))
                      .number("distance"),
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
        QCOMPARE(*mode.text("mode"), "iso");
        QCOMPARE(*mode.number("iso"), 250.0);
        const auto sampling = std::get<SamplingUpdate>(parseClientMessage(
            R"({"type":"sampling","step":0.25,"interp":"cubic","leaping":false})"));
        QCOMPARE(*sampling.number("step"), 0.25);
        QCOMPARE(*sampling.text("interp"), "cubic");
        QCOMPARE(*sampling.text("leaping"), "false");
        QVERIFY(!sampling.text("precision")); // absent: kept
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
            R"({"type":"mode","iso":300})",
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

    // fuzz_protocol found a float where an integer belongs (fuzz-regressions/): its
    // conversion was undefined; any number that is no integer in range is malformed.
    void integerFieldsOutOfRangeAreMalformed() {
        std::ifstream in(std::string(LUCENT_SOURCE_DIR) +
                             "/tests/protocol/fuzz-regressions/frame-width-float-out-of-range.bin",
                         std::ios::binary);
        const std::string found((std::istreambuf_iterator<char>(in)), {});
        QVERIFY(!found.empty());
        const auto malformed = [](const auto& read, const char* field) {
            try {
                read();
                return QString("accepted");
            } catch (const ProtocolError& e) {
                const QString what = e.what();
                return e.code() == "malformed" && e.fatal() && what.contains(field) &&
                               what.contains("must be an integer")
                           ? QString("malformed")
                           : e.code().c_str() + QString(": ") + what;
            }
        };
        QCOMPARE(malformed([&] { parseFrameMessage(found); }, "width"), QString("malformed"));
        QCOMPARE(malformed(
                     [] {
                         parseServerMessage(R"({"type":"hello","version":1e300,)"
                                            R"("backend":"cpu"})");
                     },
                     "version"),
                 QString("malformed"));
        QCOMPARE(malformed(
                     [] {
                         parseServerMessage(R"({"type":"opened","series":"s",)"
                                            R"("dims":[1,2.5,3]})");
                     },
                     "dims"),
                 QString("malformed"));
        QCOMPARE(malformed(
                     [] {
                         parseServerMessage(R"({"type":"session-state","session":"s",)"
                                            R"("members":1,"member_ids":[-1],)"
                                            R"("presenter":null,"you":1,)"
                                            R"("role":"presenter","series":null})");
                     },
                     "member_ids"),
                 QString("malformed"));
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

    // Every client message, every field set, through the one writer and the one reader.
    void everyClientMessageRoundTrips() {
        const RenderDescription d = unusualDescription();
        ClipUpdate loOnly;
        loOnly.box.lo = {0.0, 0.0, 4.0};
        const std::vector<ClientMessage> all = {
            AuthRequest{"t0ken/+=", {}},
            ListRequest{},
            OpenRequest{"1.2.840.10008#2"},
            CameraUpdate{optionUpdate(kWireCamera, d)},
            CameraUpdate{},
            TransferFunctionUpdate{"ct-bone", std::nullopt},
            TransferFunctionUpdate{std::nullopt, d.transferFunction},
            ModeUpdate{optionUpdate(kWireMode, d)},
            ClipUpdate{d.clip},
            ClipUpdate{},
            loOnly,
            QualityUpdate{Quality::Interactive},
            QualityUpdate{Quality::Still},
            SamplingUpdate{optionUpdate(kWireSampling, d)},
            SamplingUpdate{},
            SizeUpdate{640, 480},
            RenderRequest{},
            InteractionUpdate{true},
            InteractionUpdate{false},
            SessionCreate{},
            SessionJoin{"9u8ncw3mq7v5dbrf"},
            SessionHandover{7},
            SessionLeave{},
            AuthRequest{{}, "Zm9vYmFyYmF6cXV4cXV1eGNvcmdl"},
            InviteCreate{3600, "https://lecture.example.org:8443"},
            InviteCreate{},
            InviteRevoke{4},
            PointerUpdate{glm::dvec2(0.25, 0.75)},
            PointerUpdate{},
            MarkPlace{MarkKind::Arrow, {{0.1, 0.2}, {0.3, 0.4}}, {}},
            MarkPlace{MarkKind::Text, {{0.5, 0.5}}, "Foramen magnum"},
            MarksClear{},
            FreeLook{true},
            FreeLook{false},
            FreeLookRecall{},
            SlicesRequest{}, // version 4; test_slice_messages has the rest
            RecordRequest{true},
            RecordRequest{false},
            RecordingListRequest{},
            ReplayRequest{"k3mx9q2rbt7vwz4n", ReplayPace::Step},
            ReplayRequest{"k3mx9q2rbt7vwz4n", ReplayPace::Original},
            ReplayStep{},
            ReplayStop{},
        };
        std::set<std::size_t> kinds;
        for (const ClientMessage& m : all) {
            const std::string json = writeClientMessage(m);
            const ClientMessage back = parseClientMessage(json);
            QVERIFY2(back == m, json.c_str());
            QCOMPARE(writeClientMessage(back), json);
            QCOMPARE(keysOf(json).contains("type"), true);
            kinds.insert(m.index());
        }
        QCOMPARE(kinds.size(), std::variant_size_v<ClientMessage>); // none left out
        // The wire format of version 1 is unchanged.
        QCOMPARE(writeClientMessage(ClipUpdate{}), R"({"type":"clip"})");
        QCOMPARE(writeClientMessage(SizeUpdate{640, 480}),
                 R"({"height":480,"type":"size","width":640})");
        QCOMPARE(writeClientMessage(InteractionUpdate{true}),
                 R"({"state":"start","type":"interaction"})");
        QCOMPARE(writeClientMessage(
                     parseClientMessage(R"({"type":"camera","azimuth":30,"pan_up":-2.5})")),
                 R"({"azimuth":30.0,"pan_up":-2.5,"type":"camera"})");
        QCOMPARE(writeClientMessage(parseClientMessage(R"({"type":"mode","mode":"mip"})")),
                 R"({"mode":"mip","type":"mode"})");
    }

    void everyServerMessageRoundTrips() {
        const std::vector<ServerMessage> all = {
            Hello{2, "gl: llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6", {}},
            SeriesListReply{{{"1.3.12", "Head 1mm", "CT", {512, 512, 240}},
                             {"1.3.12#2", "", "MR", {64, 64, 20}}}},
            SeriesListReply{},
            Opened{"1.3.12", {512, 512, 240}, 198.4, "ct-bone", std::nullopt},
            ErrorReply{"auth-failed", "the token is not valid", true},
            SessionCreated{"9u8ncw3mq7v5dbrf"},
            SessionState{"9u8ncw3mq7v5dbrf", 2, {1, 2}, 1, 2, "follower", "1.2.826.0.1"},
            SessionState{"9u8ncw3mq7v5dbrf", 1, {3}, std::nullopt, 3, "presenter", std::nullopt},
            SessionLeft{"9u8ncw3mq7v5dbrf"},
            InviteCreated{3, "Zm9v", 1790000000, "/#invite=Zm9v", "http://h:1/#invite=Zm9v",
                          encodeQrCode("http://h:1/#invite=Zm9v")},
            InviteRevoked{3},
            PointerShown{glm::dvec2(0.0, 1.0)},
            PointerShown{},
            MarkShown{7, MarkKind::Circle, {{1.5, -2.25, 30.0}, {4.0, 5.0, 6.0}}, {}},
            MarkShown{8, MarkKind::Text, {{0.0, 0.0, 0.0}}, "Sella"},
            MarksCleared{},
            FreeLookStarted{42, 30.5, -12.0, 1.5, 400.0, -3.25, 7.0},
            FreeLookEnded{"recalled"},
            FreeLookState{3, 16},
            RecordingStarted{"k3mx9q2rbt7vwz4n"},
            RecordingStopped{"k3mx9q2rbt7vwz4n", 6, 12345, "stopped"},
            RecordingList{{{"k3mx9q2rbt7vwz4n", "1.3.12", 12345, 6, 1790000000123}}},
            RecordingList{},
            ReplayProgress{"k3mx9q2rbt7vwz4n", 2, 6, 17},
            ReplayEnded{"k3mx9q2rbt7vwz4n", "end", {}},
            ReplayEnded{"k3mx9q2rbt7vwz4n", "stopped",
                        CameraUpdate{optionUpdate(kWireCamera, unusualDescription())}},
        };
        std::set<std::size_t> kinds;
        for (const ServerMessage& m : all) {
            const std::string json = writeServerMessage(m);
            QVERIFY2(parseServerMessage(json) == m, json.c_str());
            kinds.insert(m.index());
        }
        QCOMPARE(kinds.size(), std::variant_size_v<ServerMessage>);
        // The wire format the server wrote by hand before.
        QCOMPARE(
            writeServerMessage(Opened{"1.2", {4, 5, 6}, 198.25, "ct-bone", std::nullopt}),
            R"({"dims":[4,5,6],"preset":"ct-bone","radius_mm":198.25,"series":"1.2","type":"opened"})");
        QCOMPARE(writeServerMessage(Hello{1, "cpu", {}}),
                 R"({"backend":"cpu","type":"hello","version":1})");
        QCOMPARE(
            writeServerMessage(
                SessionState{"s", 1, {3}, std::nullopt, 3, "presenter", std::nullopt}),
            R"({"member_ids":[3],"members":1,"presenter":null,"role":"presenter","series":null,"session":"s","type":"session-state","you":3})");
        // A newer server's fields are skipped; its new types are not fatal to a client.
        QCOMPARE(
            std::get<Hello>(parseServerMessage(
                                R"({"type":"hello","version":2,"backend":"cpu","gpu_mib":8000})"))
                .backend,
            "cpu");
        try {
            parseServerMessage(R"({"type":"weather","sunny":true})");
            QFAIL("an unknown type parsed");
        } catch (const ProtocolError& e) {
            QCOMPARE(e.code(), "unknown-type");
            QVERIFY(!e.fatal());
        }
        for (const char* bad : {"{", R"({"type":"hello","backend":"cpu"})",
                                R"({"type":"opened","series":"1","dims":[1,2]})",
                                R"({"type":"error","code":5,"message":"x","fatal":true})"}) {
            try {
                parseServerMessage(bad);
                QFAIL(bad);
            } catch (const ProtocolError& e) {
                QCOMPARE(e.code(), "malformed");
            }
        }
    }

    // The keys of camera, mode and sampling are the options table's wire keys.
    void optionMessagesFollowTheTable() {
        RenderDescription d = unusualDescription();
        for (const std::string_view message : {kWireCamera, kWireMode, kWireSampling}) {
            QStringList expected{"type"};
            for (const RenderOption& o : renderOptions()) {
                if (o.wireMessage == message) {
                    expected << QString::fromUtf8(o.wireKey.data(), qsizetype(o.wireKey.size()));
                }
            }
            expected.sort();
            const OptionUpdate all = optionUpdate(message, d);
            const std::string json = message == kWireCamera ? writeClientMessage(CameraUpdate{all})
                                     : message == kWireMode
                                         ? writeClientMessage(ModeUpdate{all})
                                         : writeClientMessage(SamplingUpdate{all});
            QCOMPARE(keysOf(json), expected);
        }
        QStringList sampling =
            keysOf(writeClientMessage(SamplingUpdate{optionUpdate(kWireSampling, d)}));
        QCOMPARE(sampling, (QStringList{"classification", "early_termination", "interp", "leaping",
                                        "precision", "preintegrate", "shading", "step", "type"}));
        QCOMPARE(keysOf(writeClientMessage(CameraUpdate{optionUpdate(kWireCamera, d)})),
                 (QStringList{"azimuth", "distance", "elevation", "pan_right", "pan_up", "type",
                              "zoom"}));
    }

    void samplingRefusalsNameTheField_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("key");
        QTest::newRow("above the range") << R"({"type":"sampling","early_termination":2})"
                                         << "early_termination";
        QTest::newRow("zero termination") << R"({"type":"sampling","early_termination":0})"
                                          << "early_termination";
        QTest::newRow("negative step") << R"({"type":"sampling","step":-1})"
                                       << "step";
        QTest::newRow("under the wire's floor") << R"({"type":"sampling","step":0.01})"
                                                << "step";
        QTest::newRow("unknown key") << R"({"type":"sampling","gradient":true})"
                                     << "gradient";
        QTest::newRow("not on the wire") << R"({"type":"sampling","brick":32})"
                                         << "brick";
        QTest::newRow("step as text") << R"({"type":"sampling","step":"fine"})"
                                      << "step";
        QTest::newRow("interp as number") << R"({"type":"sampling","interp":3})"
                                          << "interp";
        QTest::newRow("unknown interp") << R"({"type":"sampling","interp":"bicubic"})"
                                        << "interp";
        QTest::newRow("leaping as text") << R"({"type":"sampling","leaping":"yes"})"
                                         << "leaping";
        QTest::newRow("preintegrate as 1") << R"({"type":"sampling","preintegrate":1})"
                                           << "preintegrate";
        QTest::newRow("precision as bool") << R"({"type":"sampling","precision":true})"
                                           << "precision";
        QTest::newRow("unknown classification")
            << R"({"type":"sampling","classification":"mid","step":1})"
            << "classification";
        QTest::newRow("shading null") << R"({"type":"sampling","shading":null})"
                                      << "shading";
    }
    void samplingRefusalsNameTheField() {
        QFETCH(QString, text);
        QFETCH(QString, key);
        bool fatal = true;
        std::string message;
        QCOMPARE(errorCode(text.toStdString(), &fatal, kProtocolVersion, &message), "bad-request");
        QVERIFY(!fatal);
        QVERIFY2(QString::fromStdString(message).startsWith("sampling: "), message.c_str());
        QVERIFY2(QString::fromStdString(message).contains("'" + key + "'"), message.c_str());
    }

    void versionsAreNegotiated() {
        QCOMPARE(kProtocolVersion, 4);
        QCOMPARE(subprotocolName(2), "lucent.v2");
        QCOMPARE(subprotocolVersion("lucent.v1"), std::optional<int>(1));
        QCOMPARE(subprotocolVersion("lucent.v2"), std::optional<int>(2));
        QCOMPARE(subprotocolVersion("lucent.v3"), std::optional<int>(3));
        QCOMPARE(subprotocolVersion("lucent.v4"), std::optional<int>(4));
        for (const char* other : {"lucent.v5", "lucent.v0", "lucent.v", "lucent.v02", "lucent.v2x",
                                  "lucent.token.abc", "v2"}) {
            QVERIFY2(!subprotocolVersion(other), other);
        }
        QCOMPARE(supportedSubprotocols(),
                 (std::vector<std::string>{"lucent.v4", "lucent.v3", "lucent.v2", "lucent.v1"}));
        // Sampling came with version 2: a version 1 connection does not know the type.
        const char* sampling = R"({"type":"sampling","step":0.25,"interp":"cubic"})";
        bool fatal = false;
        std::string message;
        QCOMPARE(errorCode(sampling, &fatal, 1, &message), "unknown-type");
        QVERIFY(fatal);
        QVERIFY2(QString::fromStdString(message).contains("version 1"), message.c_str());
        QCOMPARE(errorCode(sampling, nullptr, 2), "");
        QCOMPARE(messageVersion(SamplingUpdate{}), 2);
        QCOMPARE(messageTypeVersion("sampling"), 2);
        QCOMPARE(messageTypeVersion("reboot"), 0);
        for (const char* v1 : {R"({"type":"camera","azimuth":3})", R"({"type":"list"})",
                               R"({"type":"session-leave"})"}) {
            QCOMPARE(errorCode(v1, nullptr, 1), "");
            QCOMPARE(messageVersion(parseClientMessage(v1, 1)), 1);
        }
    }

    // Invites came with version 3: an older connection that presents one is refused
    // with auth-failed saying so (fatal); its other messages are unknown types there.
    void invitesNeedVersionThree() {
        const char* inviteAuth = R"({"type":"auth","invite":"Zm9vYmFy"})";
        for (const int old : {1, 2}) {
            bool fatal = false;
            std::string message;
            QCOMPARE(errorCode(inviteAuth, &fatal, old, &message), "auth-failed");
            QVERIFY(fatal);
            QVERIFY2(message.find("version 3") != std::string::npos, message.c_str());
            QCOMPARE(errorCode(R"({"type":"invite-create"})", nullptr, old), "unknown-type");
            QCOMPARE(errorCode(R"({"type":"auth","token":"t"})", nullptr, old), "");
        }
        QCOMPARE(errorCode(inviteAuth, nullptr, 3), "");
        QCOMPARE(messageTypeVersion("invite-create"), 3);
        QCOMPARE(messageTypeVersion("invite-revoke"), 3);
        const std::string longCode(kMaxInviteCodeBytes + 1, 'a');
        const std::string tooLong = "{\"type\":\"auth\",\"invite\":\"" + longCode + "\"}";
        for (const char* bad :
             {R"({"type":"auth","invite":"a","token":"b"})", R"({"type":"auth"})",
              R"({"type":"auth","invite":""})", tooLong.c_str(),
              R"({"type":"invite-create","lifetime":0})",
              R"({"type":"invite-create","lifetime":86401})",
              R"({"type":"invite-create","lifetime":1.5})",
              R"({"type":"invite-create","origin":"https://h/path"})",
              "{\"type\":\"invite-create\",\"origin\":\"javascript:alert(1)\"}",
              R"({"type":"invite-create","code":"x"})", R"({"type":"invite-revoke","invite":0})",
              R"({"type":"invite-revoke"})"}) {
            bool fatal = true;
            QVERIFY2(errorCode(bad, &fatal, 3) == "bad-request", bad);
            QVERIFY(!fatal);
        }
    }

    // Free look came with version 4: older connections know no such type (fatal
    // unknown-type, as an old server answers); bad fields are bad-request naming them.
    void freeLookNeedsVersionFour() {
        const char* start = R"({"type":"free-look","state":"start"})";
        const char* recall = R"({"type":"free-look-recall"})";
        for (const int old : {1, 2, 3}) {
            bool fatal = false;
            std::string message;
            QCOMPARE(errorCode(start, &fatal, old, &message), "unknown-type");
            QVERIFY(fatal);
            QVERIFY2(message.find("version 4") != std::string::npos, message.c_str());
            QCOMPARE(errorCode(recall, nullptr, old), "unknown-type");
        }
        QVERIFY(parseClientMessage(start, 4) == ClientMessage{FreeLook{true}});
        QVERIFY(parseClientMessage(R"({"type":"free-look","state":"end"})", 4) ==
                ClientMessage{FreeLook{false}});
        QVERIFY(parseClientMessage(recall, 4) == ClientMessage{FreeLookRecall{}});
        QCOMPARE(messageTypeVersion("free-look"), 4);
        QCOMPARE(messageTypeVersion("free-look-recall"), 4);
        QVERIFY(!isViewMessage(FreeLook{true}));
        QCOMPARE(writeClientMessage(FreeLook{true}), R"({"state":"start","type":"free-look"})");
        const std::pair<const char*, const char*> bad[] = {
            {R"({"type":"free-look"})", "'state'"},
            {R"({"type":"free-look","state":"on"})", "'state'"},
            {R"({"type":"free-look","state":1})", "'state'"},
            {R"({"type":"free-look","state":"start","camera":{}})", "'camera'"},
            {R"({"type":"free-look-recall","all":true})", "'all'"},
        };
        for (const auto& [text, key] : bad) {
            bool fatal = true;
            std::string message;
            QVERIFY2(errorCode(text, &fatal, 4, &message) == "bad-request", text);
            QVERIFY(!fatal);
            QVERIFY2(message.find(key) != std::string::npos, message.c_str());
            QVERIFY2(message.starts_with("free-look"), message.c_str());
        }
        QCOMPARE(writeServerMessage(FreeLookEnded{"own"}),
                 R"({"reason":"own","type":"free-look-ended"})");
        QCOMPARE(writeServerMessage(FreeLookState{2, 16}),
                 R"({"limit":16,"looking":2,"type":"free-look-state"})");
    }

    // libqrencode's matrix against the format's invariants (ISO/IEC 18004): a
    // side of 17 + 4 * version, the three finder patterns with their separators,
    // the timing patterns and the dark module (zbarimg reads whole codes back in
    // test_remote_invites).
    void qrCodesKeepTheFormatsInvariants() {
        for (const std::string& text :
             {std::string("http://127.0.0.1:8765/#invite=Zm9vYmFyYmF6cXV4cXV1eGNvcmdlZ3JhdWx0"),
              std::string(300, 'x')}) {
            const QrCode qr = encodeQrCode(text);
            QVERIFY(qr.size >= 21 && (qr.size - 17) % 4 == 0);
            QCOMPARE(qr.modules.size(), std::size_t(qr.size * qr.size));
            const int version = (qr.size - 17) / 4;
            for (const auto& [ox, oy] : {std::pair{0, 0}, {qr.size - 7, 0}, {0, qr.size - 7}}) {
                for (int y = -1; y <= 7; ++y) {
                    for (int x = -1; x <= 7; ++x) {
                        if (ox + x < 0 || oy + y < 0 || ox + x >= qr.size || oy + y >= qr.size) {
                            continue;
                        }
                        // Rings about the centre: 0, 1 and 3 dark; 2 and 4 (the separator) light.
                        const int ring = std::max(std::abs(x - 3), std::abs(y - 3));
                        QCOMPARE(qr.dark(ox + x, oy + y), ring != 2 && ring != 4);
                    }
                }
            }
            for (int n = 8; n < qr.size - 8; ++n) {
                QCOMPARE(qr.dark(n, 6), n % 2 == 0);
                QCOMPARE(qr.dark(6, n), n % 2 == 0);
            }
            QVERIFY(qr.dark(8, 4 * version + 9));
        }
        QVERIFY_THROWS_EXCEPTION(std::runtime_error, encodeQrCode(std::string(8000, 'x')));
    }

    // A description, sent as view messages and applied by a server, arrives whole.
    void viewMessagesCarryTheDescription() {
        const RenderDescription want = unusualDescription();
        RenderDescription got;
        for (const ClientMessage& m : viewMessages(want)) {
            QVERIFY(isViewMessage(m));
            const ClientMessage received = parseClientMessage(writeClientMessage(m));
            QVERIFY(!applyViewMessage(received, got));
        }
        QCOMPARE(got.width, want.width);
        QCOMPARE(got.height, want.height);
        QVERIFY(got.transferFunction == want.transferFunction);
        QVERIFY(got.mode == want.mode);
        QCOMPARE(got.isoValue, want.isoValue);
        QVERIFY(got.clip.lo == want.clip.lo && got.clip.hi == want.clip.hi);
        QCOMPARE(got.camera.azimuth, want.camera.azimuth);
        QCOMPARE(got.camera.elevation, want.camera.elevation);
        QCOMPARE(got.camera.zoom, want.camera.zoom);
        QCOMPARE(got.camera.distance, want.camera.distance);
        QCOMPARE(got.camera.panRight, want.camera.panRight);
        QCOMPARE(got.camera.panUp, want.camera.panUp);
        QCOMPARE(got.sampling.step, want.sampling.step);
        QVERIFY(got.sampling.interpolation == want.sampling.interpolation);
        QVERIFY(got.sampling.classification == want.sampling.classification);
        QCOMPARE(got.sampling.preintegrate, want.sampling.preintegrate);
        QCOMPARE(got.transferFunction.shading.enabled, false);
        QCOMPARE(got.sampling.emptySpaceLeaping, want.sampling.emptySpaceLeaping);
        QVERIFY(got.sampling.precision == want.sampling.precision);
        QCOMPARE(got.sampling.earlyTermination, want.sampling.earlyTermination);
        QCOMPARE(got.sampling.brickSize, RenderDescription{}.sampling.brickSize); // not sent

        // Sides beyond the wire's are clamped; the iso value goes with isosurfaces only.
        RenderDescription odd = want;
        odd.width = 8;
        odd.height = 10000;
        odd.mode = RenderMode::Mip;
        const std::vector<ClientMessage> messages = viewMessages(odd);
        QVERIFY(std::find(messages.begin(), messages.end(), ClientMessage{SizeUpdate{16, 4096}}) !=
                messages.end());
        for (const ClientMessage& m : messages) {
            if (const auto* mode = std::get_if<ModeUpdate>(&m)) {
                QCOMPARE(*mode->text("mode"), "mip");
                QVERIFY(!mode->text("iso"));
            }
        }
        QVERIFY(applyViewMessage(TransferFunctionUpdate{"no-such-preset", std::nullopt}, got));
    }

    void errorReplyIsJson() {
        QCOMPARE(
            errorReply("auth-failed", "the token is not valid", true),
            R"({"code":"auth-failed","fatal":true,"message":"the token is not valid","type":"error"})");
    }
};

QTEST_GUILESS_MAIN(TestRemoteProtocol)
#include "test_remote_protocol.moc"
