// Frames on the wire (no network): the binary frame layout, the lossless PNG
// encoder, and the adaptive quality that holds an interactive frame rate.
#include <QTest>

#include <QByteArray>
#include <QImage>

#include <algorithm>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "protocol/AdaptiveQuality.h"
#include "protocol/PngEncoder.h"
#include "protocol/ProtocolMessages.h"

using namespace lucent;
using namespace lucent::remote;

class TestFrameProtocol : public QObject {
    Q_OBJECT

private slots:
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
};

QTEST_GUILESS_MAIN(TestFrameProtocol)
#include "test_frame_protocol.moc"
