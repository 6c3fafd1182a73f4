// 2D image stacks from real CT slices coloured and re-encoded by DCMTK and GDCM
// (make_stacks.py): decoded pixels against the source image (exact where lossless,
// a PSNR bound for JPEG baseline), YBR to RGB, palette expansion (against DCMTK's
// own rendering), MONOCHROME1 inversion, multi-frame cine frames and timing, and
// lucent-cli info listing them.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/dicom/StackLoader.h"
#include "core/stack/StackRendering.h"
#include "tests/support/CliRunner.h"
#include "tests/support/RealData.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

const fs::path kStacks = LUCENT_STACKS_DIR;

#define REQUIRE_STACKS()                                                                           \
    REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");                                                \
    QVERIFY2(fs::exists(kStacks / "rgb" / "case.dcm"), "make_stacks.py made no stacks")

std::vector<std::uint8_t> fileBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The pixels of a binary PPM (P6, 8-bit) as RGB bytes.
std::vector<std::uint8_t> ppmPixels(const fs::path& path, int& width, int& height) {
    std::ifstream in(path, std::ios::binary);
    std::string magic;
    int maxValue = 0;
    in >> magic >> width >> height >> maxValue;
    in.get();
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
    in.read(reinterpret_cast<char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
    return magic == "P6" && maxValue == 255 && in ? rgb : std::vector<std::uint8_t>{};
}

double psnr(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double d = double(a[i]) - double(b[i]);
        sum += d * d;
    }
    const double mse = sum / static_cast<double>(a.size());
    return mse == 0.0 ? INFINITY : 10.0 * std::log10(255.0 * 255.0 / mse);
}

// The one entry of a case folder, loaded as a stack.
ImageStack loadCase(const std::string& name, SeriesEntry* entry = nullptr) {
    const Catalog c = scanPath(kStacks / name);
    if (c.series.size() != 1) {
        throw LoadError(name + ": " + std::to_string(c.series.size()) + " entries, " +
                        (c.skipped.empty() ? "" : c.skipped.front().reason));
    }
    if (entry != nullptr) {
        *entry = c.series.front();
    }
    return loadStack(c.series.front());
}

} // namespace

class TestImageStack : public QObject {
    Q_OBJECT
private slots:
    void losslessColourIsExact_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<QString>("photometric");
        QTest::newRow("uncompressed RGB") << "rgb"
                                          << "RGB";
        QTest::newRow("RLE (decoder process)") << "rle"
                                               << "RGB";
        QTest::newRow("JPEG lossless") << "jpeg_lossless"
                                       << "RGB";
        QTest::newRow("JPEG 2000 lossless") << "j2k_lossless"
                                            << "RGB";
        QTest::newRow("JPEG-LS lossless (dcmdjpls)") << "jpegls_lossless"
                                                     << "RGB";
    }
    void losslessColourIsExact() {
        QFETCH(QString, name);
        QFETCH(QString, photometric);
        REQUIRE_STACKS();
        SeriesEntry entry;
        const ImageStack s = loadCase(name.toStdString(), &entry);
        QCOMPARE(entry.kind, SeriesKind::Stack);
        QCOMPARE(entry.pixels.samplesPerPixel, 3);
        QCOMPARE(QString::fromStdString(s.photometric), photometric);
        QCOMPARE(s.colour, StackColour::Rgb8);
        QCOMPARE(s.frameCount(), 1);
        int w = 0, h = 0;
        const std::vector<std::uint8_t> source = ppmPixels(kStacks / "ct.ppm", w, h);
        QCOMPARE(s.columns, w);
        QCOMPARE(s.rows, h);
        const std::span<const std::uint8_t> rgb = s.rgbFrame(0);
        QVERIFY(std::equal(rgb.begin(), rgb.end(), source.begin(), source.end()));
        // The study of the CT it was made from (img2dcm --study-from).
        QVERIFY(!s.studyUid.empty());
        QCOMPARE(QString::fromStdString(s.modality), QString("OT"));
    }

    void jpegBaselineYbr422ComesBackAsRgb() {
        REQUIRE_STACKS();
        const ImageStack s = loadCase("jpeg_baseline_ybr422");
        QCOMPARE(QString::fromStdString(s.photometric), QString("YBR_FULL_422"));
        int w = 0, h = 0;
        const std::vector<std::uint8_t> source = ppmPixels(kStacks / "ct.ppm", w, h);
        const double db = psnr(s.rgbFrame(0), source);
        qInfo("JPEG baseline YBR_FULL_422: PSNR %.1f dB against the source", db);
        QVERIFY2(db > 30.0, qPrintable(QString::number(db)));
    }

    void uncompressedYbrFullIsConverted() {
        REQUIRE_STACKS();
        // dcmdjpeg +cn: the baseline file's samples, left as YBR_FULL, converted here.
        const ImageStack ybr = loadCase("ybr_full");
        QCOMPARE(QString::fromStdString(ybr.photometric), QString("YBR_FULL"));
        int w = 0, h = 0;
        const std::vector<std::uint8_t> source = ppmPixels(kStacks / "ct.ppm", w, h);
        const double db = psnr(ybr.rgbFrame(0), source);
        QVERIFY2(db > 30.0, qPrintable(QString::number(db)));
        // The same JPEG decoded by GDCM in the decoder process: within rounding.
        const ImageStack jpeg = loadCase("jpeg_baseline_ybr422");
        int worst = 0;
        for (std::size_t i = 0; i < jpeg.rgb.size(); ++i) {
            worst = std::max(worst, std::abs(int(jpeg.rgb[i]) - int(ybr.rgb[i])));
        }
        QVERIFY2(worst <= 3, qPrintable(QString("largest difference %1").arg(worst)));
    }

    void paletteIsExpandedAsDcmtkDoes() {
        REQUIRE_STACKS();
        const ImageStack s = loadCase("palette");
        QCOMPARE(QString::fromStdString(s.photometric), QString("PALETTE COLOR"));
        QCOMPARE(s.colour, StackColour::Rgb8);
        int w = 0, h = 0;
        const std::vector<std::uint8_t> dcmtk = ppmPixels(kStacks / "palette.ppm", w, h);
        const std::span<const std::uint8_t> rgb = s.rgbFrame(0);
        QVERIFY(!dcmtk.empty());
        QVERIFY(std::equal(rgb.begin(), rgb.end(), dcmtk.begin(), dcmtk.end()));
        // dcmquant's median cut stays close to the colours it quantised.
        const std::vector<std::uint8_t> source = ppmPixels(kStacks / "ct.ppm", w, h);
        QVERIFY(psnr(rgb, source) > 30.0);
    }

    void monochrome1IsShownInverted() {
        REQUIRE_STACKS();
        SeriesEntry entry;
        const ImageStack mono1 = loadCase("monochrome1", &entry);
        QCOMPARE(entry.kind, SeriesKind::Image); // grey: still loadable as a volume
        QVERIFY(mono1.inverted);
        const Catalog original = scanPath(test::kRealData / "dcm_qa_ct/Philips_S21570/S2010/I100");
        const ImageStack mono2 = loadStack(original.series.at(0));
        QVERIFY(!mono2.inverted);
        QVERIFY(mono1.grey == mono2.grey); // the same HU; only the display differs
        QCOMPARE(mono1.window.centre, 40.0);
        QCOMPARE(mono1.window.width, 80.0);
        const GreyWindow window{40.0, 400.0};
        const ImageRGBA8 a = renderStackFrame(mono1, 0, window);
        const ImageRGBA8 b = renderStackFrame(mono2, 0, window);
        int dark = 0;
        for (std::size_t i = 0; i < a.pixelCount(); ++i) {
            QCOMPARE(int(a.pixels[4 * i]), 255 - int(b.pixels[4 * i]));
            dark += b.pixels[4 * i] < 20 ? 1 : 0;
        }
        QVERIFY(dark > 1000); // air outside the head: black in MONOCHROME2, white in 1
    }

    void ultrasoundCineFramesAndTime() {
        REQUIRE_STACKS();
        SeriesEntry entry;
        const ImageStack s = loadCase("us_cine", &entry);
        QCOMPARE(entry.kind, SeriesKind::Stack);
        QCOMPARE(entry.slices.size(), std::size_t(6));
        QCOMPARE(s.frameCount(), 6);
        QCOMPARE(QString::fromStdString(s.modality), QString("US"));
        QCOMPARE(s.frameTimeMs, 40.0);
        QCOMPARE(s.cineIntervalMs(), 40.0);
        const std::vector<std::uint8_t> source = fileBytes(kStacks / "cine_rgb.raw");
        QCOMPARE(source.size(), s.rgb.size());
        for (int f = 0; f < 6; ++f) {
            QCOMPARE(s.frames[f].timeMs, 40.0 * f);
            QVERIFY(!s.frames[f].hasPosition);
            const std::span<const std::uint8_t> frame = s.rgbFrame(f);
            QVERIFY2(std::equal(frame.begin(), frame.end(), source.begin() + frame.size() * f),
                     qPrintable(QString("frame %1").arg(f + 1)));
        }
        // Frames differ (six slices of the head), so a frame mix-up would show.
        QVERIFY(!std::equal(s.rgbFrame(0).begin(), s.rgbFrame(0).end(), s.rgbFrame(5).begin()));
    }

    void previewIsTheMiddleFrame() {
        REQUIRE_STACKS();
        const Catalog c = scanPath(kStacks / "us_cine");
        const ImageStack whole = loadStack(c.series.at(0));
        const ImageStack preview = loadStackPreview(c.series.at(0));
        QCOMPARE(preview.frameCount(), 1);
        QVERIFY(std::ranges::equal(preview.rgbFrame(0), whole.rgbFrame(3)));
    }

    void ultrasoundCineJpegDecodesEveryFrame() {
        REQUIRE_STACKS();
        const ImageStack s = loadCase("us_cine_jpeg");
        QCOMPARE(s.frameCount(), 6);
        const std::vector<std::uint8_t> source = fileBytes(kStacks / "cine_rgb.raw");
        const std::size_t bytes = s.rgbFrame(0).size();
        for (int f = 0; f < 6; ++f) {
            const double db = psnr(s.rgbFrame(f), std::span(source).subspan(bytes * f, bytes));
            QVERIFY2(db > 30.0, qPrintable(QString("frame %1: %2 dB").arg(f + 1).arg(db)));
        }
    }

    void greyXaCineWithFrameTimeVector() {
        REQUIRE_STACKS();
        const ImageStack s = loadCase("xa_cine");
        QCOMPARE(s.colour, StackColour::Grey);
        QCOMPARE(s.frameCount(), 6);
        const std::vector<std::uint8_t> source = fileBytes(kStacks / "cine_grey.raw");
        QCOMPARE(source.size(), s.grey.size());
        for (std::size_t i = 0; i < source.size(); ++i) {
            if (s.grey[i] != float(source[i])) {
                QFAIL(qPrintable(
                    QString("value %1: %2, expected %3").arg(i).arg(s.grey[i]).arg(source[i])));
            }
        }
        // FrameTimeVector 0\50\50\100\100\100: times from the first frame, mean step.
        const double times[] = {0, 50, 100, 200, 300, 400};
        for (int f = 0; f < 6; ++f) {
            QCOMPARE(s.frames[f].timeMs, times[f]);
        }
        QCOMPARE(s.frameTimeMs, 80.0);
        QCOMPARE(s.window.centre, 128.0);
        QCOMPARE(s.window.width, 200.0);
    }

    void volumeLoadsAsItsSlices() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        const Catalog c = scanPath(test::kRealData / "dcm_qa_ct/Philips_S21570/S2010");
        const SeriesEntry& e = c.series.at(0);
        QCOMPARE(e.kind, SeriesKind::Volume);
        const ImageStack s = loadStack(e);
        const Volume v = loadSeries(e);
        QCOMPARE(s.frameCount(), v.dims().z);
        QVERIFY(s.frames[3].hasPosition);
        const glm::dvec3 p = v.geometry().toPatient({0, 0, 3});
        QVERIFY(glm::length(s.frames[3].position - p) < 1e-6);
        for (int k : {0, 13, 27}) {
            for (int j = 0; j < v.dims().y; j += 37) {
                for (int i = 0; i < v.dims().x; i += 41) {
                    QCOMPARE(double(s.greyFrame(k)[std::size_t(j) * s.columns + i]),
                             v.value(i, j, k));
                }
            }
        }
    }

    void stackEntryIsNoVolume() {
        REQUIRE_STACKS();
        const Catalog c = scanPath(kStacks / "rgb");
        try {
            loadSeries(c.series.at(0));
            QFAIL("a colour stack loaded as a volume");
        } catch (const LoadError& e) {
            QVERIFY2(QString(e.what()).contains("loadStack"), e.what());
        }
    }

    void cliInfoListsColourSeries() {
        REQUIRE_STACKS();
        const test::CliRun r =
            test::runCli({"info", QString::fromStdString(kStacks.string()), "--json"});
        QCOMPARE(r.exitCode, 0);
        const QJsonObject doc = QJsonDocument::fromJson(r.out.toUtf8()).object();
        QStringList stacks;
        for (const QJsonValue s : doc["series"].toArray()) {
            if (s["kind"].toString() == "stack") {
                stacks << s["description"].toString() + ": " + s["stack"].toString();
            }
        }
        stacks.sort();
        QCOMPARE(stacks.join("; "),
                 QString("j2k_lossless: 2D stack, 1 frame, RGB; "
                         "jpeg_baseline_ybr422: 2D stack, 1 frame, YBR_FULL_422 colour; "
                         "jpeg_lossless: 2D stack, 1 frame, RGB; "
                         "jpegls_lossless: 2D stack, 1 frame, RGB; "
                         "palette: 2D stack, 1 frame, palette colour; "
                         "rgb: 2D stack, 1 frame, RGB; rle: 2D stack, 1 frame, RGB; "
                         "us_cine: 2D stack, 6 frames, RGB; "
                         "us_cine_jpeg: 2D stack, 6 frames, YBR_FULL_422 colour; "
                         "xa_cine: 2D stack, 6 frames, grey; "
                         "ybr_full: 2D stack, 1 frame, YBR_FULL colour"));
        for (const QJsonValue s : doc["skipped"].toArray()) {
            QVERIFY2(!s["reason"].toString().contains("colour"),
                     qPrintable(s["reason"].toString()));
        }
        const test::CliRun table =
            test::runCli({"info", QString::fromStdString((kStacks / "us_cine").string())});
        QVERIFY2(table.out.contains("2D stack, 6 frames, RGB"), qPrintable(table.out));
    }
};

QTEST_GUILESS_MAIN(TestImageStack)
#include "test_image_stack.moc"
