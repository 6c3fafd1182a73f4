// Version 4's MPR slices on the wire (docs/protocol.md, "Slices"): the `slices`
// message through the one writer and the one reader, its refusals naming the
// message and the key, refused as an unknown type before version 4; a slice
// frame's header; hello's window presets and opened's centre; grey PNGs.
#include <QTest>

#include <QImage>

#include <random>

#include "core/mpr/WindowPresets.h"
#include "protocol/PngEncoder.h"
#include "protocol/ProtocolMessages.h"

using namespace lucent;
using namespace lucent::remote;

namespace {

// The ProtocolError of parsing `text` on a connection of `version`; code "" when it parses.
ProtocolError refusal(std::string_view text, int version = kProtocolVersion) {
    try {
        parseClientMessage(text, version);
    } catch (const ProtocolError& e) {
        return e;
    }
    return ProtocolError("", "", false);
}

} // namespace

class TestSliceMessages : public QObject {
    Q_OBJECT

private slots:
    void slicesRoundTrip() {
        const std::vector<SlicesRequest> all = {
            SlicesRequest{},
            SlicesRequest{glm::dvec3(-12.5, 30.25, 1e3), SliceWindow{-600.0, 1500.0}, std::nullopt,
                          glm::ivec2(320, 200),
                          std::vector<Orientation>{Orientation::Sagittal, Orientation::Axial}},
            SlicesRequest{std::nullopt, std::nullopt, std::string("Bone"), std::nullopt,
                          std::vector<Orientation>{}},
            SlicesRequest{glm::dvec3(0.0), std::nullopt, std::nullopt, glm::ivec2(16, 2048),
                          std::vector<Orientation>{Orientation::Axial, Orientation::Coronal,
                                                   Orientation::Sagittal}},
        };
        for (const SlicesRequest& request : all) {
            const std::string json = writeClientMessage(request);
            const ClientMessage back = parseClientMessage(json);
            QVERIFY2(std::holds_alternative<SlicesRequest>(back), json.c_str());
            QVERIFY2(std::get<SlicesRequest>(back) == request, json.c_str());
            QCOMPARE(writeClientMessage(back), json);
            QVERIFY(!isViewMessage(back)); // owes slices, not a 3D frame
        }
        QCOMPARE(writeClientMessage(SlicesRequest{std::nullopt, std::nullopt, std::string("Brain"),
                                                  glm::ivec2(64, 32), std::nullopt}),
                 R"({"size":[64,32],"type":"slices","window":"Brain"})");
        QCOMPARE(messageTypeVersion("slices"), 4);
    }

    void slicesRefusalsNameTheKey_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("named");
        QTest::newRow("unknown field") << R"({"type":"slices","zoom":2})"
                                       << "'zoom'";
        QTest::newRow("crosshair short") << R"({"type":"slices","crosshair":[1,2]})"
                                         << "'crosshair'";
        QTest::newRow("crosshair text") << R"({"type":"slices","crosshair":[1,"2",3]})"
                                        << "'crosshair'";
        QTest::newRow("crosshair far") << R"({"type":"slices","crosshair":[1,2,1e9]})"
                                       << "'crosshair'";
        QTest::newRow("window preset") << R"({"type":"slices","window":"Sunny"})"
                                       << "'window'";
        QTest::newRow("window lower case") << R"({"type":"slices","window":"bone"})"
                                           << "'window'";
        QTest::newRow("window half") << R"({"type":"slices","window":{"center":40}})"
                                     << "'window'";
        QTest::newRow("window negative") << R"({"type":"slices","window":{"center":40,"width":-1}})"
                                         << "'window'";
        QTest::newRow("window extra")
            << R"({"type":"slices","window":{"center":40,"width":4,"gamma":2}})"
            << "'window'";
        QTest::newRow("window number") << R"({"type":"slices","window":40})"
                                       << "'window'";
        QTest::newRow("size small") << R"({"type":"slices","size":[15,100]})"
                                    << "'size'";
        QTest::newRow("size large") << R"({"type":"slices","size":[100,2049]})"
                                    << "'size'";
        QTest::newRow("size float") << R"({"type":"slices","size":[100.5,100]})"
                                    << "'size'";
        QTest::newRow("views unknown") << R"({"type":"slices","views":["oblique"]})"
                                       << "'views'";
        QTest::newRow("views twice") << R"({"type":"slices","views":["axial","axial"]})"
                                     << "'views'";
        QTest::newRow("views string") << R"({"type":"slices","views":"axial"})"
                                      << "'views'";
    }

    void slicesRefusalsNameTheKey() {
        QFETCH(QString, text);
        QFETCH(QString, named);
        const ProtocolError e = refusal(text.toStdString());
        QCOMPARE(e.code(), "bad-request");
        QVERIFY(!e.fatal());
        const QString message = QString::fromUtf8(e.what());
        QVERIFY2(message.startsWith("slices: ") && message.contains(named), qPrintable(message));
    }

    void slicesAreUnknownBeforeVersionFour() {
        for (const int old : {1, 2, 3}) {
            const ProtocolError e = refusal(R"({"type":"slices","views":["axial"]})", old);
            QCOMPARE(e.code(), "unknown-type");
            QVERIFY(e.fatal());
            QVERIFY2(QString(e.what()).contains("came with version 4"), e.what());
        }
        QCOMPARE(refusal(R"({"type":"slices"})", 4).code(), "");
    }

    void sliceFrameRoundTrip() {
        FrameHeader header;
        header.width = 320;
        header.height = 200;
        header.format = "png";
        header.seq = 9;
        header.renderMs = 3.5;
        header.encodeMs = 1.25;
        header.slice = SliceFrameInfo{Orientation::Coronal,
                                      {1.5, -2.0, 30.0},
                                      SliceWindow{40.0, 80.0},
                                      {0.0, -2.0, 12.5},
                                      {1.0, 0.0, 0.0},
                                      {0.0, 0.0, -1.0},
                                      0.75,
                                      1.0};
        const std::string image = "\x89PNG-bytes";
        const std::string message = frameMessage(header, image);
        const ParsedFrame parsed = parseFrameMessage(message);
        QVERIFY(parsed.header == header);
        QCOMPARE(std::string(parsed.image), image);
        // A 3D frame has no slice.
        header.slice.reset();
        QVERIFY(!parseFrameMessage(frameMessage(header, image)).header.slice);
        // A slice header without its plane is malformed, not a 3D frame.
        std::string broken = message;
        const auto at = broken.find("\"plane\"");
        QVERIFY(at != std::string::npos);
        broken.replace(at, 7, "\"plano\"");
        QVERIFY_THROWS_EXCEPTION(ProtocolError, parseFrameMessage(broken));
    }

    void helloListsThePresetsFromVersionFour() {
        const Hello four = helloFor(4, "cpu");
        QCOMPARE(four.windowPresets.size(), windowPresets().size());
        QCOMPARE(four.windowPresets.front().name, std::string(windowPresets().front().name));
        QCOMPARE(four.windowPresets.back().width, windowPresets().back().width);
        QVERIFY(parseServerMessage(writeServerMessage(four)) == ServerMessage(four));
        QVERIFY(helloFor(3, "cpu").windowPresets.empty());
        QCOMPARE(writeServerMessage(helloFor(3, "cpu")),
                 R"({"backend":"cpu","type":"hello","version":3})");
        const Opened opened{"1.2", {4, 5, 6}, 19.5, "ct-bone", glm::dvec3(1.5, -2.0, 3.25)};
        const std::string json = writeServerMessage(opened);
        QVERIFY2(json.find(R"("centre":[1.5,-2.0,3.25])") != std::string::npos, json.c_str());
        QVERIFY(parseServerMessage(json) == ServerMessage(opened));
    }

    void greyPngIsLossless() {
        std::mt19937 random(11);
        for (const auto& [w, h] : {std::pair{1, 1}, {17, 5}, {256, 193}}) {
            std::vector<std::uint8_t> grey(std::size_t(w) * h);
            for (std::size_t i = 0; i < grey.size(); ++i) {
                grey[i] = (i / 7) % 3 == 0 ? std::uint8_t(random()) : std::uint8_t(i);
            }
            const std::string png = encodeGreyPng(grey, w, h);
            const QImage decoded =
                QImage::fromData(QByteArray(png.data(), qsizetype(png.size())), "PNG");
            QCOMPARE(decoded.format(), QImage::Format_Grayscale8);
            QCOMPARE(decoded.width(), w);
            QCOMPARE(decoded.height(), h);
            for (int y = 0; y < h; ++y) {
                QVERIFY(std::equal(grey.begin() + std::ptrdiff_t(y) * w,
                                   grey.begin() + std::ptrdiff_t(y + 1) * w,
                                   decoded.constScanLine(y)));
            }
        }
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, encodeGreyPng({}, 2, 2));
    }
};

QTEST_GUILESS_MAIN(TestSliceMessages)
#include "test_slice_messages.moc"
