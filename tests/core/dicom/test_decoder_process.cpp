// lucent-frame-decoder as Lucent runs it (core/dicom/DecoderProcess.h): one child for
// many files, a new one when it is gone, killed when it takes too long, and a clear
// error when it cannot be found. On the NEMA JPEG 2000 images of ../shared/data.
#include <QFile>
#include <QTest>

#include <csignal>
#include <cstdlib>
#include <cstring>

#include "core/dicom/DecoderProcess.h"
#include "core/io/Catalog.h"
#include "core/io/LoadControl.h"
#include "tests/support/RealData.h"

using namespace lucent;
using lucent::test::kRealData;

namespace {

const char* kJ2kLossless = "nema_wg04/CT1/CT1_J2KR.dcm";
const char* kJ2kLossy = "nema_wg04/CT1/CT1_J2KI.dcm";

PixelLayout layoutOf(const char* file) {
    const Catalog catalog = scanPath(kRealData / file);
    return catalog.series.at(0).pixels;
}

// The stored values of the uncompressed original, as the decoder returns them.
std::vector<char> uncompressed() {
    const Catalog catalog = scanPath(kRealData / "nema_wg04/CT1/CT1_UNC.dcm");
    const SeriesEntry& e = catalog.series.at(0);
    std::vector<char> bytes(std::size_t(512) * 512 * 2);
    readNativeFrame(e.slices.at(0).file, e.slices.at(0).pixelOffset, bytes.size(), bytes.data());
    return bytes;
}

bool isZombie(pid_t pid) {
    QFile stat(QString("/proc/%1/stat").arg(pid));
    if (!stat.open(QIODevice::ReadOnly)) {
        return false;
    }
    const QByteArray line = stat.readAll();
    const qsizetype close = line.lastIndexOf(')');
    return close > 0 && line.mid(close + 2, 1) == "Z";
}

} // namespace

class TestDecoderProcess : public QObject {
    Q_OBJECT
private slots:
    void oneChildDecodesFileAfterFile() {
        REQUIRE_DATA(kJ2kLossless);
        DecoderProcess decoder;
        const std::string file = (kRealData / kJ2kLossless).string();
        const DecodedFrames first = decoder.decode(file, layoutOf(kJ2kLossless), 1);
        const pid_t pid = decoder.pid();
        QVERIFY(pid > 0);
        QVERIFY(first.buffer == uncompressed()); // lossless: the original's bytes
        const DecodedFrames lossy =
            decoder.decode((kRealData / kJ2kLossy).string(), layoutOf(kJ2kLossy), 1);
        QCOMPARE(lossy.buffer.size(), first.buffer.size());
        QCOMPARE(decoder.pid(), pid); // the same child
    }

    void aDecoderGoneIsStartedAgain() {
        REQUIRE_DATA(kJ2kLossless);
        DecoderProcess decoder;
        const std::string file = (kRealData / kJ2kLossless).string();
        (void)decoder.decode(file, layoutOf(kJ2kLossless), 1);
        const pid_t first = decoder.pid();
        QCOMPARE(::kill(first, SIGKILL), 0);
        // Dead (a zombie until the decoder reaps it) before the next file, as a decoder
        // killed while Lucent was idle would be.
        QTRY_VERIFY(isZombie(first));
        const DecodedFrames again = decoder.decode(file, layoutOf(kJ2kLossless), 1);
        QVERIFY(again.buffer == uncompressed());
        QVERIFY(decoder.pid() > 0 && decoder.pid() != first);
    }

    void aChildIsReplacedAfterItsShareOfFiles() {
        REQUIRE_DATA(kJ2kLossless);
        DecoderProcess decoder(DecoderProcess::kTimeout, 2);
        const std::string file = (kRealData / kJ2kLossless).string();
        (void)decoder.decode(file, layoutOf(kJ2kLossless), 1);
        const pid_t first = decoder.pid();
        (void)decoder.decode(file, layoutOf(kJ2kLossless), 1);
        QCOMPARE(decoder.pid(), first);
        const DecodedFrames third = decoder.decode(file, layoutOf(kJ2kLossless), 1);
        QVERIFY(decoder.pid() != first); // what its codecs leaked went back with it
        QVERIFY(third.buffer == uncompressed());
    }

    // JPEG, RLE and big endian go through the child too: each equals the original.
    void everyGdcmSyntaxIsDecodedInTheChild_data() {
        QTest::addColumn<QString>("file");
        for (const char* v : {"JPLL", "RLE", "J2KR"}) {
            QTest::newRow(v) << QString("nema_wg04/CT1/CT1_%1.dcm").arg(v);
        }
    }
    void everyGdcmSyntaxIsDecodedInTheChild() {
        QFETCH(QString, file);
        REQUIRE_DATA(file.toStdString());
        DecoderProcess decoder;
        const std::string name = file.toStdString();
        QVERIFY(decoder.decode((kRealData / name).string(), layoutOf(name.c_str()), 1).buffer ==
                uncompressed());
        QVERIFY(decoder.pid() > 0);
    }

    void aDecoderTooSlowIsStopped() {
        REQUIRE_DATA(kJ2kLossless);
        // Decoding 512x512 lossless takes tens of milliseconds; one is not enough.
        DecoderProcess decoder(std::chrono::milliseconds(1));
        const std::string file = (kRealData / kJ2kLossless).string();
        try {
            (void)decoder.decode(file, layoutOf(kJ2kLossless), 1);
            QFAIL("decoded within 1 ms");
        } catch (const LoadError& e) {
            QVERIFY2(std::strstr(e.what(), "decoding took longer than") != nullptr, e.what());
            QVERIFY2(std::strstr(e.what(), file.c_str()) != nullptr, e.what());
        }
        QCOMPARE(decoder.pid(), pid_t(0)); // killed and reaped
    }

    void aMissingDecoderIsNamed() {
        REQUIRE_DATA(kJ2kLossless);
        QVERIFY(!frameDecoderExecutable().empty()); // built beside this test
        ::setenv("LUCENT_FRAME_DECODER", "/nonexistent/lucent-frame-decoder", 1);
        DecoderProcess decoder;
        try {
            (void)decoder.decode((kRealData / kJ2kLossless).string(), layoutOf(kJ2kLossless), 1);
            QFAIL("decoded without a decoder");
        } catch (const LoadError& e) {
            QVERIFY2(std::strstr(e.what(), "cannot start /nonexistent/lucent-frame-decoder"),
                     e.what());
        }
        ::unsetenv("LUCENT_FRAME_DECODER");
    }
};

QTEST_APPLESS_MAIN(TestDecoderProcess)
#include "test_decoder_process.moc"
