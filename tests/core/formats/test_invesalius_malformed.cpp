// Damaged InVesalius projects: cut gzip streams, entries over their caps, odd
// tar members, plists with wrong types or broken XML. Each must load or end in
// a LoadError naming the file and what is wrong.
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "core/formats/InVesaliusProject.h"
#include "core/io/LoadControl.h"
#include "tests/core/formats/FormatTestFiles.h"

using namespace lucent;
using namespace lucent::test;
namespace fs = std::filesystem;

namespace {

struct PlistFields {
    std::string dtype = "<string>int16</string>";
    std::string filename = "<string>matrix.dat</string>";
    std::string shape =
        "<array><integer>2</integer><integer>3</integer><integer>4</integer></array>";
    std::string spacing = "<array><real>0.5</real><real>0.75</real><real>2</real></array>";
    std::string extra; // more dict entries
};

std::string plistOf(const PlistFields& f) {
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<plist version=\"1.0\">\n<dict>\n"
           "<key>matrix</key><dict><key>dtype</key>" +
           f.dtype + "<key>filename</key>" + f.filename + "<key>shape</key>" + f.shape +
           "</dict>\n<key>spacing</key>" + f.spacing + "\n" + f.extra + "</dict>\n</plist>\n";
}

const std::string tinyMatrix(2 * 2 * 3 * 4, '\1');

// A pax record: "<length> <key>=<value>\n", the length counting itself.
std::string paxRecord(const std::string& key, const std::string& value) {
    const std::size_t body = key.size() + value.size() + 3; // ' ', '=', '\n'
    std::size_t length = body + 1;
    while (std::to_string(length).size() + body != length) {
        ++length;
    }
    return std::to_string(length) + " " + key + "=" + value + "\n";
}

std::string readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

class TestInVesaliusMalformed : public QObject {
    Q_OBJECT

private slots:
    void longNamesLinksAndFoldersAreHandled() {
        QTemporaryDir dir;
        const fs::path path = dirOf(dir) / "members.inv3";
        const std::string folder = std::string(150, 'd') + "/";
        writeTarMembers(path,
                        {{"folder", "", '5'},
                         {folder + "main.plist", "", '2'}, // a symlink is no member
                         {"././@LongLink", folder + "main.plist" + '\0', 'L'},
                         {"short/main.plist", plistOf({}), '0'},
                         {"PaxHeaders/matrix.dat", paxRecord("path", folder + "matrix.dat"), 'x'},
                         {"short/matrix.dat", tinyMatrix, '0'}});
        const Volume v = readInVesalius(path);
        QCOMPARE(v.dims(), glm::ivec3(4, 3, 2));
        QCOMPARE(v.value(3, 2, 1), 257.0);
    }

    // libarchive reports a cut gzip stream as soon as its read-ahead meets the cut:
    // 1 MiB of incompressible voxels keep the cut well past main.plist.
    void cutGzipNamesTheEntry() {
        QTemporaryDir dir;
        const fs::path whole = dirOf(dir) / "whole.inv3";
        std::string matrix(64 * 64 * 128 * 2, '\0');
        std::mt19937 random(7);
        for (char& c : matrix) {
            c = static_cast<char>(random());
        }
        PlistFields f;
        f.shape = "<array><integer>64</integer><integer>64</integer><integer>128</integer></array>";
        writeTarGz(whole, {{"p/main.plist", plistOf(f)}, {"p/matrix.dat", matrix}});
        QCOMPARE(readInVesalius(whole).dims(), glm::ivec3(128, 64, 64));

        const std::string bytes = readAll(whole);
        const fs::path cut = dirOf(dir) / "cut.inv3";
        writeText(cut, bytes.substr(0, bytes.size() * 3 / 4));
        QCOMPARE(readInVesaliusHeader(cut).geometry.dims, glm::ivec3(128, 64, 64));
        QString e = loadErrorOf([&] { readInVesalius(cut); });
        QVERIFY2(e.startsWith(QString::fromStdString(cut.string()) + ": p/matrix.dat: ") &&
                     e.contains("truncated gzip input"),
                 qPrintable(e));

        const fs::path stub = dirOf(dir) / "stub.inv3"; // inside the gzip header
        writeText(stub, bytes.substr(0, 6));
        e = loadErrorOf([&] { readInVesaliusHeader(stub); });
        QVERIFY2(e.contains("stub.inv3") && e.contains("not a tar archive"), qPrintable(e));
    }

    void notTarInsideGzip() {
        QTemporaryDir dir;
        const fs::path path = dirOf(dir) / "text.inv3";
        const std::string text(2000, 'x');
        writeGz(path, text.data(), text.size());
        const QString e = loadErrorOf([&] { readInVesaliusHeader(path); });
        QVERIFY2(e.contains("text.inv3") && e.contains("not a tar archive"), qPrintable(e));
    }

    void entriesOverTheirCaps() {
        QTemporaryDir dir;
        const fs::path big = dirOf(dir) / "bigplist.inv3";
        writeTarGz(big, {{"p/main.plist", std::string((std::size_t{16} << 20) + 1, ' ')}});
        QString e = loadErrorOf([&] { readInVesaliusHeader(big); });
        QVERIFY2(e.contains("bigplist.inv3") && e.contains("main.plist is implausibly large"),
                 qPrintable(e));

        const fs::path longName = dirOf(dir) / "longname.inv3";
        writeTarMembers(longName, {{"././@LongLink", std::string((1 << 20) + 10, 'n'), 'L'},
                                   {"p/main.plist", plistOf({}), '0'}});
        e = loadErrorOf([&] { readInVesaliusHeader(longName); });
        QVERIFY2(e.contains("longname.inv3") && e.contains("too large"), qPrintable(e));

        const fs::path shortMatrix = dirOf(dir) / "short.inv3";
        writeTarGz(shortMatrix, {{"p/main.plist", plistOf({})}, {"p/matrix.dat", "abc"}});
        e = loadErrorOf([&] { readInVesalius(shortMatrix); });
        QVERIFY2(e.contains("short.inv3") && e.contains("p/matrix.dat is truncated: expected 48"),
                 qPrintable(e));
    }

    // libplist reads a number it cannot parse as 0: the geometry check names it.
    void unreadableRealIsZeroSpacing() {
        QTemporaryDir dir;
        const fs::path path = dirOf(dir) / "nan.inv3";
        PlistFields f;
        f.spacing = "<array><real>1</real><real>abc</real><real>1</real></array>";
        writeTarGz(path, {{"p/main.plist", plistOf(f)}, {"p/matrix.dat", tinyMatrix}});
        const QString e = loadErrorOf([&] { readInVesaliusHeader(path); });
        QVERIFY2(e.contains("nan.inv3") && e.contains("spacing of the") &&
                     e.contains("must be positive, is 0"),
                 qPrintable(e));
    }

    void badPlists_data() {
        QTest::addColumn<QString>("plist");
        QTest::addColumn<QString>("error");
        PlistFields f;
        f.spacing = "<array><string>1</string><string>1</string><string>1</string></array>";
        QTest::newRow("spacing strings")
            << QString::fromStdString(plistOf(f)) << "key 'spacing' is not an array of 3 numbers";
        f = {};
        f.dtype = "<integer>16</integer>";
        QTest::newRow("dtype integer")
            << QString::fromStdString(plistOf(f)) << "key 'matrix.dtype' is not a string";
        f = {};
        f.dtype = "<string>complex64</string>";
        QTest::newRow("dtype unknown") << QString::fromStdString(plistOf(f))
                                       << "'matrix.dtype' names an unsupported type 'complex64'";
        f = {};
        f.shape = "<array><integer>2</integer><integer>-3</integer><integer>4</integer></array>";
        QTest::newRow("shape negative")
            << QString::fromStdString(plistOf(f)) << "'matrix.shape' must hold positive integers";
        f = {};
        f.shape = "<array><integer>2</integer><integer>3</integer></array>";
        QTest::newRow("shape short")
            << QString::fromStdString(plistOf(f)) << "'matrix.shape' is not an array of 3 numbers";
        f = {};
        f.filename = "<string>../matrix.dat</string>";
        QTest::newRow("filename path")
            << QString::fromStdString(plistOf(f)) << "'matrix.filename' is not a plain file name";
        QTest::newRow("top array") << "<plist version=\"1.0\"><array/></plist>"
                                   << "main.plist: top level is not a dict";
        f = {};
        f.spacing = "<array><real>1</real><real>1</real><real>1</real>"; // never closed
        QTest::newRow("unclosed") << QString::fromStdString(plistOf(f))
                                  << "main.plist: not a well-formed XML property";
        f = {};
        f.extra = "<key>x</key><float>1</float>";
        QTest::newRow("unknown element")
            << QString::fromStdString(plistOf(f)) << "main.plist: not a well-formed XML property";
        f = {};
        std::string deep;
        for (int i = 0; i < 100; ++i) {
            deep = "<array>" + deep + "</array>";
        }
        f.extra = "<key>deep</key>" + deep;
        QTest::newRow("deep") << QString::fromStdString(plistOf(f))
                              << "main.plist: nesting deeper than 64 levels";
        QTest::newRow("binary") << "bplist00\xd1\x01\x02"
                                << "main.plist: a binary plist";
    }

    void badPlists() {
        QFETCH(QString, plist);
        QFETCH(QString, error);
        QTemporaryDir dir;
        const fs::path path = dirOf(dir) / "bad.inv3";
        writeTarGz(path, {{"p/main.plist", plist.toStdString()}, {"p/matrix.dat", tinyMatrix}});
        const QString e = loadErrorOf([&] { readInVesaliusHeader(path); });
        QVERIFY2(e.startsWith(QString::fromStdString(path.string()) + ": main.plist: ") &&
                     e.contains(error),
                 qPrintable(e));
    }
};

QTEST_GUILESS_MAIN(TestInVesaliusMalformed)
#include "test_invesalius_malformed.moc"
