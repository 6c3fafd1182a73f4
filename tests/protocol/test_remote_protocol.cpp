// The protocol's messages: one writer and one reader each way, the options table
// behind camera, mode and sampling (no network; versions in
// test_protocol_versions.cpp, frames in test_frame_protocol.cpp).
#include <QTest>

#include <QJsonDocument>
#include <QJsonObject>

#include <fstream>
#include <iterator>
#include <set>

#include "protocol/ProtocolMessages.h"
#include "tests/protocol/ProtocolErrors.h"

using namespace lucent;
using namespace lucent::remote;
using lucent::remote::test::errorCode;

namespace {

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
