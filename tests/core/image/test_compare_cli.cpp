// lucent-cli compare, run as a user runs it: the one output line, exit status
// and messages for bad input.
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTest>

#include "tests/support/CliRunner.h"

#include <filesystem>
#include <fstream>

#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"

using namespace lucent;

namespace {

ImageRGBA8 pattern(int w, int h, int shift) {
    ImageRGBA8 image = ImageRGBA8::filled(w, h, 255);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            image.at(x, y, 0) = static_cast<std::uint8_t>((x * 7 + shift) % 256);
            image.at(x, y, 1) = static_cast<std::uint8_t>((y * 5) % 256);
            image.at(x, y, 2) = static_cast<std::uint8_t>(((x ^ y) * 3 + shift) % 256);
        }
    }
    return image;
}

} // namespace

class TestCompareCli : public QObject {
    Q_OBJECT
private:
    QTemporaryDir dir_;
    QString path(const char* name) const { return dir_.filePath(name); }
    void write(const ImageRGBA8& image, const char* name) const {
        writePng(image, path(name).toStdString());
    }

private slots:
    void initTestCase() {
        QVERIFY(dir_.isValid());
        write(pattern(40, 30, 0), "a.png");
        write(pattern(40, 30, 0), "a-copy.png");
        write(pattern(40, 30, 9), "b.png");
        write(pattern(30, 40, 0), "rotated.png");
        write(pattern(8, 8, 0), "tiny.png");
        std::ofstream(path("text.png").toStdString()) << "not a png\n";
    }

    void identicalImages() {
        const test::CliRun r = test::runCli({"compare", path("a.png"), path("a-copy.png")});
        QCOMPARE(r.exitCode, 0);
        QCOMPARE(r.out, QString("psnr_db=inf ssim=1.0000\n"));
    }

    void differentImages() {
        const test::CliRun r = test::runCli({"compare", path("a.png"), path("b.png")});
        QCOMPARE(r.exitCode, 0);
        const QRegularExpression line("^psnr_db=(\\d+\\.\\d\\d) ssim=(-?\\d\\.\\d{4})\\n$");
        const QRegularExpressionMatch m = line.match(r.out);
        QVERIFY2(m.hasMatch(), qPrintable(r.out));
        const ImageRGBA8 a = pattern(40, 30, 0);
        const ImageRGBA8 b = pattern(40, 30, 9);
        QCOMPARE(m.captured(1), QString::number(psnr(a, b), 'f', 2));
        QCOMPARE(m.captured(2), QString::number(ssim(a, b), 'f', 4));
        QVERIFY(m.captured(2).toDouble() < 1.0);
    }

    void sizeMismatchIsBadInput() {
        const test::CliRun r = test::runCli({"compare", path("a.png"), path("rotated.png")});
        QCOMPARE(r.exitCode, 3);
        QVERIFY(r.out.isEmpty());
        QVERIFY2(r.err.contains("40x30") && r.err.contains("30x40") &&
                     r.err.contains(path("rotated.png")),
                 qPrintable(r.err));
        const test::CliRun tiny = test::runCli({"compare", path("tiny.png"), path("tiny.png")});
        QCOMPARE(tiny.exitCode, 3);
        QVERIFY2(tiny.err.contains("11x11"), qPrintable(tiny.err));
    }

    void badFilesAreNamed() {
        for (const char* name : {"missing.png", "text.png"}) {
            const test::CliRun r = test::runCli({"compare", path("a.png"), path(name)});
            QCOMPARE(r.exitCode, 3);
            QVERIFY2(r.err.contains(path(name)), qPrintable(r.err));
        }
    }

    void usageErrors() {
        QCOMPARE(test::runCli({"compare", path("a.png")}).exitCode, 2);
        QCOMPARE(test::runCli({"compare"}).exitCode, 2);
        QCOMPARE(test::runCli({"compare", path("a.png"), path("b.png"), path("b.png")}).exitCode,
                 2);
        QCOMPARE(test::runCli({"compare", "--bogus", path("a.png"), path("b.png")}).exitCode, 2);
        const test::CliRun help = test::runCli({"compare", "--help"});
        QCOMPARE(help.exitCode, 0);
        QVERIFY(help.out.contains("psnr_db"));
    }
};

QTEST_GUILESS_MAIN(TestCompareCli)
#include "test_compare_cli.moc"
