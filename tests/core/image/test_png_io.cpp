// readPng/writePng: RGBA round trip, every colour type and bit depth libpng
// can write normalised to RGBA8, atomic writes, and errors that name the file.
#include <QTemporaryDir>
#include <QTest>

#include <png.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include "core/image/PngIO.h"
#include "core/io/LoadControl.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

// What the test writes with libpng directly: raw rows in PNG's own layout.
struct RawPng {
    int width = 0;
    int height = 0;
    int colorType = PNG_COLOR_TYPE_RGB;
    int bitDepth = 8;
    bool interlaced = false;
    std::vector<std::vector<png_byte>> rows;
    std::vector<png_color> palette;
    std::vector<png_byte> paletteAlpha; // tRNS for palette images
};

bool writeRawUnchecked(png_structp png, png_infop info, std::FILE* f, RawPng& raw,
                       png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) {
        return false;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, static_cast<png_uint_32>(raw.width),
                 static_cast<png_uint_32>(raw.height), raw.bitDepth, raw.colorType,
                 raw.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (!raw.palette.empty()) {
        png_set_PLTE(png, info, raw.palette.data(), static_cast<int>(raw.palette.size()));
    }
    if (!raw.paletteAlpha.empty()) {
        png_set_tRNS(png, info, raw.paletteAlpha.data(), static_cast<int>(raw.paletteAlpha.size()),
                     nullptr);
    }
    png_write_info(png, info);
    if (raw.bitDepth == 16) {
        png_set_swap(png); // rows below hold 16-bit samples little-endian
    }
    png_write_image(png, rows);
    png_write_end(png, info);
    return true;
}

bool writeRaw(const fs::path& file, RawPng raw) {
    std::FILE* f = std::fopen(file.c_str(), "wb");
    if (f == nullptr) {
        return false;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    std::vector<png_bytep> rows;
    for (auto& r : raw.rows) {
        rows.push_back(r.data());
    }
    const bool ok = writeRawUnchecked(png, info, f, raw, rows.data());
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return ok;
}

void put16(std::vector<png_byte>& row, std::uint16_t v) {
    row.push_back(static_cast<png_byte>(v & 0xff));
    row.push_back(static_cast<png_byte>(v >> 8));
}

std::uint8_t to8(std::uint16_t v) {
    return static_cast<std::uint8_t>(std::lround(v / 257.0));
}

ImageRGBA8 randomImage(int w, int h) {
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> d(0, 255);
    ImageRGBA8 image = ImageRGBA8::filled(w, h);
    for (auto& p : image.pixels) {
        p = static_cast<std::uint8_t>(d(rng));
    }
    return image;
}

QString loadErrorOf(const fs::path& file) {
    try {
        readPng(file);
    } catch (const LoadError& e) {
        return QString::fromUtf8(e.what());
    }
    return {};
}

} // namespace

class TestPngIO : public QObject {
    Q_OBJECT
private slots:
    void rgbaRoundTrip() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "round trip.png";
        const ImageRGBA8 image = randomImage(37, 23);
        writePng(image, file);
        QVERIFY(readPng(file) == image);
        // Overwriting goes through a temporary file that does not stay behind.
        const ImageRGBA8 other = ImageRGBA8::filled(5, 4, 77);
        writePng(other, file);
        QVERIFY(readPng(file) == other);
        int entries = 0;
        for ([[maybe_unused]] const auto& e : fs::directory_iterator(file.parent_path())) {
            ++entries;
        }
        QCOMPARE(entries, 1);
    }

    void readsGrey8() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "grey8.png";
        RawPng raw{3, 2, PNG_COLOR_TYPE_GRAY, 8, false, {{0, 128, 255}, {1, 2, 3}}, {}, {}};
        QVERIFY(writeRaw(file, raw));
        const ImageRGBA8 image = readPng(file);
        QCOMPARE(image.width, 3);
        QCOMPARE(image.height, 2);
        for (int y = 0; y < 2; ++y) {
            for (int x = 0; x < 3; ++x) {
                const std::uint8_t v = raw.rows[y][x];
                QCOMPARE(image.at(x, y, 0), v);
                QCOMPARE(image.at(x, y, 1), v);
                QCOMPARE(image.at(x, y, 2), v);
                QCOMPARE(image.at(x, y, 3), std::uint8_t(255));
            }
        }
    }

    void readsGreyAlpha16AndRgb16() {
        QTemporaryDir dir;
        const std::vector<std::uint16_t> values = {0, 257, 0x1234, 0x80ff, 65535};
        const int w = static_cast<int>(values.size());

        RawPng ga{w, 1, PNG_COLOR_TYPE_GRAY_ALPHA, 16, false, {{}}, {}, {}};
        for (std::uint16_t v : values) {
            put16(ga.rows[0], v);
            put16(ga.rows[0], static_cast<std::uint16_t>(65535 - v));
        }
        const fs::path gaFile = fs::path(dir.path().toStdString()) / "ga16.png";
        QVERIFY(writeRaw(gaFile, ga));
        const ImageRGBA8 g = readPng(gaFile);
        for (int x = 0; x < w; ++x) {
            const std::uint16_t v = values[static_cast<std::size_t>(x)];
            QCOMPARE(g.at(x, 0, 0), to8(v));
            QCOMPARE(g.at(x, 0, 2), to8(v));
            QCOMPARE(g.at(x, 0, 3), to8(static_cast<std::uint16_t>(65535 - v)));
        }

        RawPng rgb{w, 2, PNG_COLOR_TYPE_RGB, 16, false, {{}, {}}, {}, {}};
        for (std::uint16_t v : values) {
            for (auto& row : rgb.rows) {
                put16(row, v);
                put16(row, static_cast<std::uint16_t>(v / 2));
                put16(row, static_cast<std::uint16_t>(65535 - v));
            }
        }
        const fs::path rgbFile = fs::path(dir.path().toStdString()) / "rgb16.png";
        QVERIFY(writeRaw(rgbFile, rgb));
        const ImageRGBA8 c = readPng(rgbFile);
        QCOMPARE(c.height, 2);
        for (int x = 0; x < w; ++x) {
            const std::uint16_t v = values[static_cast<std::size_t>(x)];
            QCOMPARE(c.at(x, 1, 0), to8(v));
            QCOMPARE(c.at(x, 1, 1), to8(static_cast<std::uint16_t>(v / 2)));
            QCOMPARE(c.at(x, 1, 2), to8(static_cast<std::uint16_t>(65535 - v)));
            QCOMPARE(c.at(x, 1, 3), std::uint8_t(255));
        }
    }

    void readsPaletteWithTransparencyAndInterlacedRgb() {
        QTemporaryDir dir;
        // 4-bit palette, two pixels per byte: indices 0 1 2 / 2 1 0.
        RawPng pal{3,
                   2,
                   PNG_COLOR_TYPE_PALETTE,
                   4,
                   false,
                   {{0x01, 0x20}, {0x21, 0x00}},
                   {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}},
                   {10, 255}};
        const fs::path palFile = fs::path(dir.path().toStdString()) / "palette.png";
        QVERIFY(writeRaw(palFile, pal));
        const ImageRGBA8 p = readPng(palFile);
        const std::uint8_t want0[4] = {255, 0, 0, 10};
        const std::uint8_t want2[4] = {0, 0, 255, 255}; // past the tRNS entries: opaque
        for (int c = 0; c < 4; ++c) {
            QCOMPARE(p.at(0, 0, c), want0[c]);
            QCOMPARE(p.at(2, 1, c), want0[c]);
            QCOMPARE(p.at(2, 0, c), want2[c]);
        }
        QCOMPARE(p.at(1, 1, 1), std::uint8_t(255));

        RawPng rgb{9, 7, PNG_COLOR_TYPE_RGB, 8, true, {}, {}, {}};
        for (int y = 0; y < 7; ++y) {
            std::vector<png_byte> row;
            for (int x = 0; x < 9; ++x) {
                row.insert(row.end(), {png_byte(x * 20), png_byte(y * 30), png_byte(x + y)});
            }
            rgb.rows.push_back(row);
        }
        const fs::path rgbFile = fs::path(dir.path().toStdString()) / "adam7.png";
        QVERIFY(writeRaw(rgbFile, rgb));
        const ImageRGBA8 r = readPng(rgbFile);
        for (int y = 0; y < 7; ++y) {
            for (int x = 0; x < 9; ++x) {
                QCOMPARE(r.at(x, y, 0), std::uint8_t(x * 20));
                QCOMPARE(r.at(x, y, 1), std::uint8_t(y * 30));
                QCOMPARE(r.at(x, y, 2), std::uint8_t(x + y));
                QCOMPARE(r.at(x, y, 3), std::uint8_t(255));
            }
        }
    }

    void errorsNameTheFile() {
        QTemporaryDir dir;
        const fs::path root = dir.path().toStdString();
        const fs::path missing = root / "missing.png";
        QString m = loadErrorOf(missing);
        QVERIFY2(m.contains(QString::fromStdString(missing.string())) && m.contains("no such"),
                 qPrintable(m));

        const fs::path text = root / "notes.png";
        std::ofstream(text) << "this is not a PNG file at all\n";
        m = loadErrorOf(text);
        QVERIFY2(m.contains(QString::fromStdString(text.string())) && m.contains("not a PNG"),
                 qPrintable(m));

        const fs::path empty = root / "empty.png";
        std::ofstream{empty};
        QVERIFY(loadErrorOf(empty).contains(QString::fromStdString(empty.string())));

        m = loadErrorOf(root);
        QVERIFY2(m.contains("folder"), qPrintable(m));

        // A valid PNG cut in half, and one with a damaged byte in its data.
        const fs::path good = root / "good.png";
        writePng(randomImage(64, 64), good);
        std::ifstream in(good, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), {});
        const fs::path cut = root / "cut.png";
        std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 2));
        m = loadErrorOf(cut);
        QVERIFY2(m.contains(QString::fromStdString(cut.string())), qPrintable(m));
        std::string damaged = bytes;
        damaged[damaged.size() / 2] = static_cast<char>(damaged[damaged.size() / 2] ^ 0x5a);
        const fs::path bad = root / "damaged.png";
        std::ofstream(bad, std::ios::binary).write(damaged.data(), std::streamsize(damaged.size()));
        m = loadErrorOf(bad);
        QVERIFY2(m.contains(QString::fromStdString(bad.string())), qPrintable(m));
    }

    void writeErrorsNameTheFile() {
        QTemporaryDir dir;
        const fs::path target = fs::path(dir.path().toStdString()) / "no such folder" / "out.png";
        try {
            writePng(ImageRGBA8::filled(4, 4), target);
            QFAIL("writePng into a missing folder succeeded");
        } catch (const std::runtime_error& e) {
            QVERIFY2(QString(e.what()).contains(QString::fromStdString(target.string())), e.what());
        }
        const fs::path ok = fs::path(dir.path().toStdString()) / "empty.png";
        QVERIFY_THROWS_EXCEPTION(std::runtime_error, writePng(ImageRGBA8{}, ok));
        QVERIFY(!fs::exists(ok));
    }
};

QTEST_APPLESS_MAIN(TestPngIO)
#include "test_png_io.moc"
