// Mesh files read back: binary STL (size 84 + 50 n, a header that does not
// start with "solid" and says SPACE=LPS), binary PLY (normals, colours and the
// svr values bit for bit), legacy VTK (big-endian points, POINT_DATA with
// normals and svr), OBJ (LPS comment first). Writing is atomic: a missing
// folder or a full disk is an error naming the file, and a file already there
// stays as it was.
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <bit>
#include <csignal>
#include <cstring>
#include <fstream>
#include <sstream>

#include <sys/resource.h>

#include "core/formats/MeshFiles.h"

using namespace lucent;

namespace {

// A closed tetrahedron, outward normals.
TriangleMesh tetrahedron() {
    TriangleMesh m;
    m.vertices = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return m;
}

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

template <class T> T at(const std::string& bytes, std::size_t offset, bool bigEndian = false) {
    std::array<char, sizeof(T)> b;
    std::memcpy(b.data(), bytes.data() + offset, sizeof(T));
    if (bigEndian) {
        std::reverse(b.begin(), b.end());
    }
    return std::bit_cast<T>(b);
}

} // namespace

class TestMeshFiles : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    std::string path(const char* name) const { return dir_.filePath(name).toStdString(); }

private slots:
    void stlIsBinaryWithAnHonestHeader() {
        const TriangleMesh m = tetrahedron();
        writeMesh(m, path("t.stl"), MeshFormat::Stl, {"solid iso=300HU", {}, 0, 0, 1});
        const std::string bytes = readAll(path("t.stl"));
        QCOMPARE(bytes.size(), std::size_t(84 + 50 * 4));
        QVERIFY(bytes.rfind("solid", 0) != 0);
        QVERIFY(bytes.substr(0, 80).find("SPACE=LPS") != std::string::npos);
        QCOMPARE(at<std::uint32_t>(bytes, 80), 4u);
        // The last facet: normal (1,1,1)/sqrt(3), then its vertices 1, 2, 3.
        const std::size_t facet = 84 + 50 * 3;
        QCOMPARE(at<float>(bytes, facet), float(1.0 / std::sqrt(3.0)));
        QCOMPARE(at<float>(bytes, facet + 12), 10.0f);
        QCOMPARE(at<float>(bytes, facet + 12 + 36 - 4), 10.0f);
    }

    void plyCarriesSvrBitForBit() {
        const TriangleMesh m = tetrahedron();
        const std::vector<float> svr = {0.1f, 1.0f / 3.0f, 2.5f, 1e-7f};
        writeMesh(m, path("t.ply"), MeshFormat::Ply, {"iso=300HU", svr, 5.0, 0.0, 2.5});
        const std::string bytes = readAll(path("t.ply"));
        const std::size_t end = bytes.find("end_header\n");
        QVERIFY(end != std::string::npos);
        const std::string header = bytes.substr(0, end);
        QVERIFY(header.rfind("ply\nformat binary_little_endian 1.0\n", 0) == 0);
        QVERIFY(header.find("comment SPACE=LPS") != std::string::npos);
        QVERIFY(header.find("comment svr_radius_mm 5") != std::string::npos);
        QVERIFY(header.find("element vertex 4\n") != std::string::npos);
        QVERIFY(header.find("property float svr\n") != std::string::npos);
        // x y z nx ny nz (24 bytes), r g b (3), quality, svr (8): 35 bytes a vertex.
        const std::size_t vertices = end + 11;
        for (std::size_t v = 0; v < 4; ++v) {
            const std::size_t at0 = vertices + v * 35;
            QCOMPARE(at<float>(bytes, at0), float(m.vertices[v].x));
            QCOMPARE(std::bit_cast<std::uint32_t>(at<float>(bytes, at0 + 31)),
                     std::bit_cast<std::uint32_t>(svr[v]));
        }
        // Viridis ends: the lowest value dark violet, the highest yellow.
        QCOMPARE(std::uint8_t(bytes[vertices + 3 * 35 + 24]), std::uint8_t(0x44)); // 1e-7: low
        QCOMPARE(std::uint8_t(bytes[vertices + 2 * 35 + 24]), std::uint8_t(0xfd)); // 2.5: high
        const std::size_t faces = vertices + 4 * 35;
        QCOMPARE(bytes.size(), faces + 4 * 13);
        QCOMPARE(std::uint8_t(bytes[faces]), std::uint8_t(3));
        QCOMPARE(at<std::int32_t>(bytes, faces + 1 + 4), 2);
    }

    void vtkHasPointDataForSlicerAndParaView() {
        const TriangleMesh m = tetrahedron();
        writeMesh(m, path("t.vtk"), MeshFormat::Vtk, {"", {1, 2, 3, 4}, 2.0, 1, 4});
        const std::string bytes = readAll(path("t.vtk"));
        QVERIFY(bytes.rfind("# vtk DataFile Version 3.0\n", 0) == 0);
        QVERIFY(bytes.find("SPACE=LPS") < bytes.find("\nBINARY\n"));
        const std::size_t points = bytes.find("POINTS 4 float\n");
        QVERIFY(points != std::string::npos);
        QCOMPARE(at<float>(bytes, points + 15 + 12, true), 10.0f); // vertex 1's x, big-endian
        QVERIFY(bytes.find("POLYGONS 4 16\n") != std::string::npos);
        QVERIFY(bytes.find("POINT_DATA 4\nNORMALS Normals float\n") != std::string::npos);
        const std::size_t scalars = bytes.find("SCALARS svr float 1\nLOOKUP_TABLE default\n");
        QVERIFY(scalars != std::string::npos);
        QCOMPARE(at<float>(bytes, scalars + 41 + 12, true), 4.0f);
    }

    void objStartsWithTheSpace() {
        writeMesh(tetrahedron(), path("t.obj"), MeshFormat::Obj);
        const std::string text = readAll(path("t.obj"));
        QVERIFY(text.rfind("# SPACE=LPS\n", 0) == 0);
        std::istringstream lines(text);
        std::string line;
        int v = 0, vn = 0, f = 0;
        while (std::getline(lines, line)) {
            v += line.rfind("v ", 0) == 0;
            vn += line.rfind("vn ", 0) == 0;
            f += line.rfind("f ", 0) == 0;
        }
        QCOMPARE(v, 4);
        QCOMPARE(vn, 4);
        QCOMPARE(f, 4);
        QVERIFY(text.find("f 1//1 3//3 2//2\n") != std::string::npos);
    }

    // VTK's readers (those of 3D Slicer and ParaView) read every file: the
    // counts, PLY's colours and VTK's svr point array.
    void vtkReadsEveryFile() {
        const TriangleMesh m = tetrahedron();
        const MeshFileContent content{"iso=300HU", {0.5f, 1.0f, 1.5f, 2.0f}, 3.0, 0.5, 2.0};
        for (const char* name : {"r.stl", "r.ply", "r.vtk", "r.obj"}) {
            writeMesh(m, path(name), meshFormatOf(name), content);
            QProcess python;
            python.start("/usr/bin/python3",
                         {LUCENT_SOURCE_DIR "/tests/core/formats/read_mesh_with_vtk.py",
                          dir_.filePath(name)});
            QVERIFY(python.waitForFinished(60000));
            const QString out = QString::fromUtf8(python.readAllStandardOutput()).trimmed();
            const QString err = QString::fromUtf8(python.readAllStandardError());
            if (err.contains("No module named 'vtk'") ||
                python.error() == QProcess::FailedToStart) {
                QFAIL("VTK's Python bindings are missing: install python3-vtk9 "
                      "(packaging/install-deps.sh)");
            }
            QVERIFY2(python.exitCode() == 0, qPrintable(err));
            const QStringList fields = out.split(' ');
            // STL repeats each vertex per facet; VTK's reader merges them back.
            QVERIFY2(fields.value(0).toInt() == 4 || fields.value(0).toInt() == 12,
                     qPrintable(name + (": " + out)));
            QVERIFY2(fields.value(1) == "4", qPrintable(name + (": " + out)));
            // VTK 9.1's PLY reader takes colours and normals, not other
            // properties (the svr values are read back above, bit for bit).
            if (QString(name).endsWith("ply")) {
                QVERIFY2(out.contains("RGB") && out.contains("Normals"),
                         qPrintable(name + (": " + out)));
            }
            if (QString(name).endsWith("vtk")) {
                QVERIFY2(out.contains("svr") && out.endsWith("(0.5, 2.0)"),
                         qPrintable(name + (": " + out)));
            }
        }
    }

    void formatsByExtension() {
        QCOMPARE(meshFormatOf("skull.STL"), MeshFormat::Stl);
        QCOMPARE(meshFormatOf("a/b.vtk"), MeshFormat::Vtk);
        try {
            (void)meshFormatOf("skull.txt");
            QFAIL("accepted .txt");
        } catch (const std::invalid_argument& e) {
            QVERIFY(std::string(e.what()).find("skull.txt") != std::string::npos);
        }
    }

    void badInputIsRefused() {
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 writeMesh(TriangleMesh{}, path("e.stl"), MeshFormat::Stl));
        QVERIFY_THROWS_EXCEPTION(
            std::invalid_argument,
            writeMesh(tetrahedron(), path("e.ply"), MeshFormat::Ply, {"", {1.0f}, 1, 0, 1}));
        QVERIFY(!QFile::exists(dir_.filePath("e.stl")) && !QFile::exists(dir_.filePath("e.ply")));
    }

    void aMissingFolderNamesTheFile() {
        const std::string file = path("no/such/folder/t.stl");
        try {
            writeMesh(tetrahedron(), file, MeshFormat::Stl);
            QFAIL("wrote into a missing folder");
        } catch (const std::runtime_error& e) {
            QVERIFY2(std::string(e.what()).find(file) != std::string::npos, e.what());
        }
    }

    // A full disk (the file size limit stands in for it): the write fails
    // with the file's name, the file already there is untouched and no
    // temporary file is left.
    void aFullDiskLeavesTheOldFileWhole() {
        TriangleMesh big = tetrahedron();
        for (int n = 0; n < 2000; ++n) {
            big.triangles.push_back(big.triangles[std::size_t(n % 4)]);
        }
        const std::string file = path("full.stl");
        writeMesh(tetrahedron(), file, MeshFormat::Stl);
        const std::string before = readAll(file);
        const auto previousHandler = std::signal(SIGXFSZ, SIG_IGN);
        rlimit old{};
        getrlimit(RLIMIT_FSIZE, &old);
        rlimit small = old;
        small.rlim_cur = 4096;
        QCOMPARE(setrlimit(RLIMIT_FSIZE, &small), 0);
        bool threw = false;
        try {
            writeMesh(big, file, MeshFormat::Stl);
        } catch (const std::runtime_error& e) {
            threw = std::string(e.what()).find(file) != std::string::npos;
        }
        setrlimit(RLIMIT_FSIZE, &old);
        std::signal(SIGXFSZ, previousHandler);
        QVERIFY(threw);
        QCOMPARE(readAll(file), before);
        QCOMPARE(QDir(dir_.path()).entryList(QDir::Files | QDir::Hidden).filter(".tmp").size(), 0);
    }
};

QTEST_GUILESS_MAIN(TestMeshFiles)
#include "test_mesh_files.moc"
