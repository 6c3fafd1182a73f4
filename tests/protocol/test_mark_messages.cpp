// The pointer and mark messages (version 4): their refusals name the message and
// the key, older connections do not know them, and the frame header carries the
// projection that places a mark's anchors on the image (old headers without it).
#include <QTest>

#include "core/scene/ImageProjection.h"
#include "core/scene/ViewFrame.h"
#include "protocol/ProtocolMessages.h"

using namespace lucent;
using namespace lucent::remote;

namespace {

// The refusal's code and message; "" when it parses.
std::pair<std::string, std::string> refusal(const std::string& text, int version = 4,
                                            bool* fatal = nullptr) {
    try {
        parseClientMessage(text, version);
    } catch (const ProtocolError& e) {
        if (fatal) {
            *fatal = e.fatal();
        }
        return {e.code(), e.what()};
    }
    return {};
}

std::string points(int n) {
    std::string s = "[";
    for (int i = 0; i < n; ++i) {
        s += (i ? "," : "") + std::string("[0.5,0.5]");
    }
    return s + "]";
}

} // namespace

class TestMarkMessages : public QObject {
    Q_OBJECT
private slots:
    void refusalsNameTheMessageAndTheKey_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("named");
        const auto row = [](const char* name, const std::string& text, const char* named) {
            QTest::newRow(name) << QString::fromStdString(text) << QString(named);
        };
        row("pointer x only", R"({"type":"pointer","x":0.5})", "pointer: give both 'x' and 'y'");
        row("pointer out of range", R"({"type":"pointer","x":1.5,"y":0})", "pointer: 'x'");
        row("pointer string", R"({"type":"pointer","x":0,"y":"top"})", "pointer: 'y'");
        row("pointer unknown", R"({"type":"pointer","x":0,"y":0,"z":1})",
            "pointer: unknown field 'z'");
        row("no kind", R"({"type":"mark","points":[[0,0],[1,1]]})", "mark: 'kind'");
        row("bad kind", R"({"type":"mark","kind":"star","points":[[0,0],[1,1]]})", "mark: 'kind'");
        row("arrow of one", R"({"type":"mark","kind":"arrow","points":[[0,0]]})",
            "mark: 'points' must be an array of 2 points for a arrow mark");
        row("circle of three", R"({"type":"mark","kind":"circle","points":)" + points(3) + "}",
            "mark: 'points'");
        row("freehand too long",
            R"({"type":"mark","kind":"freehand","points":)" + points(513) + "}", "2 to 512 points");
        row("point outside", R"({"type":"mark","kind":"arrow","points":[[0,0],[1,-0.1]]})",
            "mark: each of 'points'");
        row("point of three", R"({"type":"mark","kind":"arrow","points":[[0,0],[1,1,1]]})",
            "mark: each of 'points'");
        row("text missing", R"({"type":"mark","kind":"text","points":[[0,0]]})", "mark: 'text'");
        row("text empty", R"({"type":"mark","kind":"text","points":[[0,0]],"text":""})",
            "mark: 'text'");
        row("text too long",
            "{\"type\":\"mark\",\"kind\":\"text\",\"points\":[[0,0]],\"text\":\"" +
                std::string(201, 'a') + "\"}",
            "1 to 200 characters");
        row("text on an arrow",
            R"({"type":"mark","kind":"arrow","points":[[0,0],[1,1]],"text":"x"})",
            "mark: 'text' belongs to text marks");
        row("mark unknown", R"({"type":"mark","kind":"text","points":[[0,0]],"text":"a","id":1})",
            "mark: unknown field 'id'");
        row("clear with a field", R"({"type":"marks-clear","all":true})",
            "marks-clear: unknown field 'all'");
    }
    void refusalsNameTheMessageAndTheKey() {
        QFETCH(QString, text);
        QFETCH(QString, named);
        bool fatal = true;
        const auto [code, message] = refusal(text.toStdString(), 4, &fatal);
        QCOMPARE(code, std::string("bad-request"));
        QVERIFY(!fatal);
        QVERIFY2(message.find(named.toStdString()) != std::string::npos, message.c_str());
    }

    void theLimitsHold() {
        // 200 characters are 200 code points, whatever their bytes.
        std::string accents;
        for (int i = 0; i < 200; ++i) {
            accents += "\xc3\xa9"; // é
        }
        const auto text = parseClientMessage(
            "{\"type\":\"mark\",\"kind\":\"text\",\"points\":[[0,1]],\"text\":\"" + accents + "\"}",
            4);
        QCOMPARE(std::get<MarkPlace>(text).text, accents);
        const auto freehand = parseClientMessage(
            R"({"type":"mark","kind":"freehand","points":)" + points(512) + "}", 4);
        QCOMPARE(std::get<MarkPlace>(freehand).points.size(), kMaxFreehandPoints);
        QVERIFY(!std::get<PointerUpdate>(parseClientMessage(R"({"type":"pointer"})", 4)).at);
    }

    void olderVersionsDoNotKnowThem() {
        for (const char* text : {R"({"type":"pointer","x":0,"y":0})",
                                 R"({"type":"mark","kind":"arrow","points":[[0,0],[1,1]]})",
                                 R"({"type":"marks-clear"})"}) {
            for (const int old : {1, 2, 3}) {
                bool fatal = false;
                const auto [code, message] = refusal(text, old, &fatal);
                QCOMPARE(code, std::string("unknown-type"));
                QVERIFY(fatal);
                QVERIFY2(message.find("came with version 4") != std::string::npos, message.c_str());
            }
        }
        QCOMPARE(messageTypeVersion("pointer"), 4);
        QCOMPARE(messageTypeVersion("mark"), 4);
        QCOMPARE(messageTypeVersion("marks-clear"), 4);
    }

    void theFrameCarriesItsProjection() {
        VolumeGeometry g;
        g.dims = {64, 64, 40};
        g.spacing = {0.8, 0.8, 2.0};
        Camera camera;
        camera.azimuth = 30.0;
        camera.zoom = 1.7;
        const ViewFrame frame = makeViewFrame(g, camera, 300, 200);
        FrameHeader header;
        header.width = 300;
        header.height = 200;
        header.format = "png";
        header.seq = 3;
        header.projection = imageProjection(frame);
        const std::string message = frameMessage(header, "image");
        const ParsedFrame back = parseFrameMessage(message);
        QVERIFY(back.header == header);
        // The projection takes the ray of a pixel back to that pixel.
        const glm::dvec3 p = frame.eye + 250.0 * frame.rayDirection(40.0, 170.0, 300, 200);
        const auto uv = projectToImage(*back.header.projection, p);
        QVERIFY(uv);
        QVERIFY(std::abs(uv->x * 300 - 40.5) < 1e-9 && std::abs(uv->y * 200 - 170.5) < 1e-9);
        // An older server's header has none; a broken one is malformed.
        header.projection.reset();
        QVERIFY(!parseFrameMessage(frameMessage(header, "")).header.projection);
        const std::string bad = R"({"width":1,"height":1,"format":"png","seq":1,)"
                                R"("quality":"still","projection":[1,2,3]})";
        std::string broken = {0, 0, 0, char(bad.size())};
        broken += bad;
        try {
            parseFrameMessage(broken);
            QFAIL("a projection of three numbers was read");
        } catch (const ProtocolError& e) {
            QCOMPARE(e.code(), "malformed");
        }
    }
};

QTEST_APPLESS_MAIN(TestMarkMessages)
#include "test_mark_messages.moc"
