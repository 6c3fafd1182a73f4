// Protocol versions: what each version of a client may send (sampling from 2,
// invites from 3, free look from 4) and the QR codes of invites (no network).
#include <QTest>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>

#include "protocol/ProtocolMessages.h"
#include "tests/protocol/ProtocolErrors.h"

using namespace lucent;
using namespace lucent::remote;
using lucent::remote::test::errorCode;

class TestProtocolVersions : public QObject {
    Q_OBJECT

private slots:
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
};

QTEST_APPLESS_MAIN(TestProtocolVersions)
#include "test_protocol_versions.moc"
