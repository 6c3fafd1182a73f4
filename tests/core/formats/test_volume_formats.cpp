#include <QTemporaryDir>
#include <QTest>

#include <cmath>
#include <filesystem>
#include <functional>

#include "core/formats/InVesaliusProject.h"
#include "core/formats/MetaImage.h"
#include "core/formats/Nifti.h"
#include "core/io/LoadControl.h"
#include "tests/core/formats/FormatTestFiles.h"

using namespace lucent;
using namespace lucent::test;
namespace fs = std::filesystem;

namespace {

const fs::path demoProject = "/usr/share/doc/invesalius-examples/examples/Cranium.inv3";

const std::string plainHeader = "ObjectType = Image\nNDims = 3\nDimSize = 3 2 2\n"
                                "ElementSpacing = 1 1 1\n";

} // namespace

class TestVolumeFormats : public QObject {
    Q_OBJECT

private slots:
    void metaImageRoundTrip_data();
    void metaImageRoundTrip();
    void metaImageBigEndianAndDirection();
    void metaImageSlices();
    void metaImageCompressed();
    void metaImageUCharLocal();
    void metaImageWriteFailureLeavesNothing();
    void niftiSform_data();
    void niftiSform();
    void niftiQform();
    void niftiScaling();
    void niftiBigEndian();
    void badInput();
    void inVesaliusSynthetic();
    void inVesaliusMissingKey();
    void inVesaliusDemo();
};

// A slab of slices read from its byte range equals the same slices of the whole.
void TestVolumeFormats::metaImageSlices() {
    QTemporaryDir dir;
    const fs::path mhd = dirOf(dir) / "volume.mhd";
    const VolumeGeometry g = obliqueGeometry();
    const Volume v = patternVolume<std::int16_t>(g);
    writeMetaImage(v, mhd);
    QVERIFY(metaImageHasSliceRanges(mhd));
    const int k0 = 1, k1 = g.dims.z - 1;
    const Volume slab = readMetaImageSlices(mhd, k0, k1);
    QCOMPARE(slab.dims(), glm::ivec3(g.dims.x, g.dims.y, k1 - k0));
    QVERIFY(glm::length(slab.geometry().origin - g.toPatient({0.0, 0.0, double(k0)})) < 1e-9);
    for (int k = k0; k < k1; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                QCOMPARE(slab.value(i, j, k - k0), v.value(i, j, k));
            }
        }
    }
    QVERIFY_THROWS_EXCEPTION(LoadError, readMetaImageSlices(mhd, 0, g.dims.z + 1));
    QVERIFY_THROWS_EXCEPTION(LoadError, readMetaImageSlices(mhd, 2, 2));
}

void TestVolumeFormats::metaImageRoundTrip_data() {
    QTest::addColumn<int>("type");
    QTest::newRow("int16") << static_cast<int>(VoxelType::Int16);
    QTest::newRow("uint16") << static_cast<int>(VoxelType::UInt16);
    QTest::newRow("float32") << static_cast<int>(VoxelType::Float32);
}

void TestVolumeFormats::metaImageRoundTrip() {
    QFETCH(int, type);
    QTemporaryDir dir;
    const fs::path mhd = dirOf(dir) / "volume.mhd";
    const VolumeGeometry g = obliqueGeometry();
    const auto voxelType = static_cast<VoxelType>(type);
    Volume v = voxelType == VoxelType::Int16    ? patternVolume<std::int16_t>(g)
               : voxelType == VoxelType::UInt16 ? patternVolume<std::uint16_t>(g)
                                                : patternVolume<float>(g);
    v.modality = "CT";
    v.description = "Head\nwith contrast";
    writeMetaImage(v, mhd);

    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dirOf(dir))) {
        names.push_back(e.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    QCOMPARE(names, (std::vector<std::string>{"volume.mhd", "volume.raw"}));
    QCOMPARE(fs::file_size(dirOf(dir) / "volume.raw"), v.byteCount());

    const VolumeFileHeader header = readMetaImageHeader(mhd);
    QVERIFY(sameGeometry(header.geometry, g));
    QCOMPARE(header.voxelType, voxelType);
    const Volume back = readMetaImage(mhd);
    QVERIFY(sameGeometry(back.geometry(), g));
    QCOMPARE(back.type(), voxelType);
    QCOMPARE(back.modality, std::string("CT"));
    QCOMPARE(back.description, std::string("Head with contrast"));
    const bool same = voxelType == VoxelType::Int16    ? matchesPattern<std::int16_t>(back)
                      : voxelType == VoxelType::UInt16 ? matchesPattern<std::uint16_t>(back)
                                                       : matchesPattern<float>(back);
    QVERIFY(same);
}

void TestVolumeFormats::metaImageBigEndianAndDirection() {
    QTemporaryDir dir;
    const fs::path mhd = dirOf(dir) / "msb.mhd";
    // ITK's convention: the first three numbers are the unit vector of the i axis.
    test::writeText(mhd, "ObjectType = Image\nNDims = 3\nDimSize = 3 2 2\n"
                         "ElementSpacing = 0.5 2 3\nOffset = 10 20 30\n"
                         "TransformMatrix = 0 1 0 -1 0 0 0 0 1\nAnatomicalOrientation = PLI\n"
                         "ElementByteOrderMSB = True\nElementType = MET_SHORT\n"
                         "ElementDataFile = msb.raw\n");
    const std::vector<std::int16_t> values{-1024, 1, 2, 300, -5, 32767, 7, 8, 9, 10, 11, -32768};
    test::writeText(dirOf(dir) / "msb.raw", bigEndianShorts(values));
    const Volume v = readMetaImage(mhd);
    QCOMPARE(v.type(), VoxelType::Int16);
    const auto voxels = v.voxels<std::int16_t>();
    QVERIFY(std::equal(voxels.begin(), voxels.end(), values.begin(), values.end()));
    const VolumeGeometry& g = v.geometry();
    QVERIFY(near(g.toPatient({1, 0, 0}), {10.0, 20.5, 30.0}, 1e-12));
    QVERIFY(near(g.toPatient({0, 1, 0}), {8.0, 20.0, 30.0}, 1e-12));
    QVERIFY(near(g.toPatient({0, 0, 1}), {10.0, 20.0, 33.0}, 1e-12));
}

void TestVolumeFormats::metaImageCompressed() {
    QTemporaryDir dir;
    const fs::path mhd = dirOf(dir) / "z.mhd";
    std::vector<float> values(12);
    for (std::size_t n = 0; n < values.size(); ++n) {
        values[n] = static_cast<float>(n) * 1.5f - 4.0f;
    }
    uLongf size = compressBound(values.size() * sizeof(float));
    std::vector<Bytef> packed(size);
    QCOMPARE(compress2(packed.data(), &size, reinterpret_cast<const Bytef*>(values.data()),
                       values.size() * sizeof(float), 6),
             Z_OK);
    test::writeBytes(dirOf(dir) / "z.zraw", packed.data(), size);
    test::writeText(mhd, plainHeader +
                             "CompressedData = True\nCompressedDataSize = " + std::to_string(size) +
                             "\nElementType = MET_FLOAT\nElementDataFile = z.zraw\n");
    const Volume v = readMetaImage(mhd);
    QCOMPARE(v.type(), VoxelType::Float32);
    const auto voxels = v.voxels<float>();
    QVERIFY(std::equal(voxels.begin(), voxels.end(), values.begin(), values.end()));

    // A cut-off compressed stream is truncated data, not a crash.
    test::writeBytes(dirOf(dir) / "z.zraw", packed.data(), size / 2);
    const QString error = loadErrorOf([&] { readMetaImage(mhd); });
    QVERIFY2(error.contains("z.mhd"), qPrintable(error));
}

void TestVolumeFormats::metaImageUCharLocal() {
    QTemporaryDir dir;
    const fs::path mha = dirOf(dir) / "bytes.mha";
    std::string data;
    for (int n = 0; n < 12; ++n) {
        data += static_cast<char>(n * 23); // up to 253: unsigned
    }
    test::writeText(mha, plainHeader + "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n" + data);
    const Volume v = readMetaImage(mha);
    QCOMPARE(v.type(), VoxelType::Int16);
    for (int n = 0; n < 12; ++n) {
        QCOMPARE(v.voxels<std::int16_t>()[static_cast<std::size_t>(n)], n * 23);
    }
}

void TestVolumeFormats::metaImageWriteFailureLeavesNothing() {
    QTemporaryDir dir;
    const Volume v = patternVolume<std::int16_t>(obliqueGeometry());
    QVERIFY_THROWS_EXCEPTION(std::runtime_error,
                             writeMetaImage(v, dirOf(dir) / "missing" / "volume.mhd"));
    QVERIFY(fs::is_empty(dirOf(dir)));
}

void TestVolumeFormats::niftiSform_data() {
    QTest::addColumn<bool>("gzipped");
    QTest::newRow("nii") << false;
    QTest::newRow("nii.gz") << true;
}

void TestVolumeFormats::niftiSform() {
    QFETCH(bool, gzipped);
    QTemporaryDir dir;
    const fs::path path = dirOf(dir) / (gzipped ? "rot.nii.gz" : "rot.nii");
    const std::array<short, 3> dims{4, 3, 2};
    std::vector<std::int16_t> values(24);
    for (std::size_t n = 0; n < values.size(); ++n) {
        values[n] = static_cast<std::int16_t>(100 * n - 1000);
    }
    // RAS affine: 30 degrees about z, spacing 0.9 x 1.1 x 2, origin (10, -20, 30).
    const float c = std::cos(0.5235988f), s = std::sin(0.5235988f);
    test::NiftiHeader h(dims, 4, 16);
    h.setSform({{{0.9f * c, -1.1f * s, 0.0f, 10.0f},
                 {0.9f * s, 1.1f * c, 0.0f, -20.0f},
                 {0.0f, 0.0f, 2.0f, 30.0f}}});
    std::memcpy(h.bytes.data() + 148, "test volume", 11);
    const auto bytes = h.file(values.data(), values.size() * 2);
    gzipped ? test::writeGz(path, bytes.data(), bytes.size())
            : test::writeBytes(path, bytes.data(), bytes.size());

    const Volume v = readNifti(path);
    QCOMPARE(v.dims(), glm::ivec3(4, 3, 2));
    QCOMPARE(v.type(), VoxelType::Int16);
    QCOMPARE(v.description, std::string("test volume"));
    QVERIFY(near(v.geometry().spacing, {0.9, 1.1, 2.0}, 1e-6));
    // Voxel (2, 1, 1) in RAS: (10, -20, 30) + 2 * col0 + 1 * col1 + 1 * col2; LPS negates x, y.
    const glm::dvec3 ras(10.0 + 1.8 * c - 1.1 * s, -20.0 + 1.8 * s + 1.1 * c, 32.0);
    QVERIFY(near(v.geometry().toPatient({2, 1, 1}), {-ras.x, -ras.y, ras.z}, 1e-5));
    QCOMPARE(v.value(2, 1, 1), 100.0 * (2 + 4 * 1 + 12 * 1) - 1000.0);
    QVERIFY(near(readNiftiHeader(path).geometry.origin, {-10.0, 20.0, 30.0}, 1e-6));
}

void TestVolumeFormats::niftiQform() {
    QTemporaryDir dir;
    const fs::path path = dirOf(dir) / "q.nii";
    test::NiftiHeader h({2, 2, 2}, 16, 32);
    h.put<short>(252, 1);    // qform_code; sform_code stays 0
    h.put<float>(76, -1.0f); // qfac -1: the k axis is flipped
    h.put<float>(80, 0.5f);
    h.put<float>(84, 0.75f);
    h.put<float>(88, 3.0f);
    h.put<float>(264, static_cast<float>(std::sqrt(0.5))); // 90 degrees about z
    h.put<float>(268, 1.0f);
    h.put<float>(272, 2.0f);
    h.put<float>(276, 3.0f);
    const std::array<float, 8> values{0, 1, 2, 3, 4, 5, 6, 7.5f};
    const auto bytes = h.file(values.data(), sizeof values);
    test::writeBytes(path, bytes.data(), bytes.size());
    const Volume v = readNifti(path);
    const VolumeGeometry& g = v.geometry();
    // RAS columns: i -> (0, 1, 0), j -> (-1, 0, 0), k -> (0, 0, -1); LPS negates x and y.
    QVERIFY(near(g.direction[0], {0, -1, 0}, 1e-6));
    QVERIFY(near(g.direction[1], {1, 0, 0}, 1e-6));
    QVERIFY(near(g.direction[2], {0, 0, -1}, 1e-6));
    QVERIFY(near(g.spacing, {0.5, 0.75, 3.0}, 1e-6));
    QVERIFY(near(g.origin, {-1.0, -2.0, 3.0}, 1e-6));
    QCOMPARE(v.value(1, 1, 1), 7.5);
}

void TestVolumeFormats::niftiScaling() {
    QTemporaryDir dir;
    const fs::path path = dirOf(dir) / "scaled.nii";
    const std::array<std::uint8_t, 8> values{0, 1, 2, 3, 100, 200, 254, 255};
    auto write = [&](float slope, float inter) {
        test::NiftiHeader h({2, 2, 2}, 2, 8);
        h.put<float>(112, slope);
        h.put<float>(116, inter);
        const auto bytes = h.file(values.data(), values.size());
        test::writeBytes(path, bytes.data(), bytes.size());
        return readNifti(path);
    };
    const Volume integral = write(2.0f, -10.0f); // every uint8 maps into int16 exactly
    QCOMPARE(integral.type(), VoxelType::Int16);
    QCOMPARE(integral.value(1, 1, 1), 500.0);
    QCOMPARE(integral.value(0, 0, 0), -10.0);
    const Volume fractional = write(0.5f, 1.0f);
    QCOMPARE(fractional.type(), VoxelType::Float32);
    QCOMPARE(fractional.value(1, 0, 1), 101.0);
    QCOMPARE(fractional.value(1, 0, 0), 1.5);
    const Volume unscaled = write(0.0f, 5.0f); // slope 0 means no scaling
    QCOMPARE(unscaled.type(), VoxelType::Int16);
    QCOMPARE(unscaled.value(1, 1, 1), 255.0);
}

void TestVolumeFormats::niftiBigEndian() {
    QTemporaryDir dir;
    const fs::path path = dirOf(dir) / "big.nii";
    test::NiftiHeader h({3, 2, 2}, 4, 16, true);
    h.put<float>(80, 0.8f);
    const std::vector<std::int16_t> values{-1024, 1, 2, 300, -5, 32767, 7, 8, 9, 10, 11, -32768};
    auto bytes = h.file(nullptr, 0);
    const std::string data = bigEndianShorts(values);
    bytes.insert(bytes.end(), data.begin(), data.end());
    test::writeBytes(path, bytes.data(), bytes.size());
    const Volume v = readNifti(path);
    QCOMPARE(v.dims(), glm::ivec3(3, 2, 2));
    QVERIFY(near(v.geometry().spacing, {0.8, 1.0, 1.0}, 1e-6));
    const auto voxels = v.voxels<std::int16_t>();
    QVERIFY(std::equal(voxels.begin(), voxels.end(), values.begin(), values.end()));
}

void TestVolumeFormats::badInput() {
    QTemporaryDir dir;
    const fs::path d = dirOf(dir);
    // Missing and truncated raw files.
    test::writeText(d / "noraw.mhd", plainHeader + "ElementType = MET_SHORT\nElementDataFile = "
                                                   "absent.raw\n");
    QString e = loadErrorOf([&] { readMetaImage(d / "noraw.mhd"); });
    QVERIFY2(e.contains("noraw.mhd") && e.contains("absent.raw"), qPrintable(e));
    test::writeText(d / "short.mhd", plainHeader + "ElementType = MET_SHORT\nElementDataFile = "
                                                   "short.raw\n");
    test::writeText(d / "short.raw", std::string(23, '\0'));
    e = loadErrorOf([&] { readMetaImage(d / "short.mhd"); });
    QVERIFY2(e.contains("short.mhd") && e.contains("truncated"), qPrintable(e));
    test::writeText(d / "type.mhd", plainHeader + "ElementType = MET_LONG_LONG\n"
                                                  "ElementDataFile = short.raw\n");
    e = loadErrorOf([&] { readMetaImageHeader(d / "type.mhd"); });
    QVERIFY2(e.contains("type.mhd") && e.contains("MET_LONG_LONG"), qPrintable(e));
    test::writeText(d / "text.mhd", "just some text\n");
    e = loadErrorOf([&] { readMetaImage(d / "text.mhd"); });
    QVERIFY2(e.contains("text.mhd"), qPrintable(e));

    // NIfTI: wrong magic, unsupported datatype, truncated voxels (plain and gzipped).
    const std::array<std::int16_t, 8> values{};
    test::NiftiHeader bad({2, 2, 2}, 4, 16);
    std::memcpy(bad.bytes.data() + 344, "xyz\0", 4);
    auto bytes = bad.file(values.data(), sizeof values);
    test::writeBytes(d / "magic.nii", bytes.data(), bytes.size());
    e = loadErrorOf([&] { readNifti(d / "magic.nii"); });
    QVERIFY2(e.contains("magic.nii") && e.contains("magic"), qPrintable(e));
    test::NiftiHeader complex({2, 2, 2}, 32, 64);
    bytes = complex.file(values.data(), sizeof values);
    test::writeBytes(d / "complex.nii", bytes.data(), bytes.size());
    e = loadErrorOf([&] { readNiftiHeader(d / "complex.nii"); });
    QVERIFY2(e.contains("complex.nii") && e.contains("complex64"), qPrintable(e));
    test::NiftiHeader good({2, 2, 2}, 4, 16);
    bytes = good.file(values.data(), sizeof values - 3);
    test::writeBytes(d / "cut.nii", bytes.data(), bytes.size());
    e = loadErrorOf([&] { readNifti(d / "cut.nii"); });
    QVERIFY2(e.contains("cut.nii") && e.contains("truncated"), qPrintable(e));
    test::writeGz(d / "cut.nii.gz", bytes.data(), bytes.size());
    e = loadErrorOf([&] { readNifti(d / "cut.nii.gz"); });
    QVERIFY2(e.contains("cut.nii.gz"), qPrintable(e));

    // Nonexistent files, and a project that is not a tar.gz.
    for (const auto& [name, read] : std::vector<std::pair<std::string, std::function<void()>>>{
             {"nothing.mhd", [&] { readMetaImage(d / "nothing.mhd"); }},
             {"nothing.nii", [&] { readNifti(d / "nothing.nii"); }},
             {"nothing.inv3", [&] { readInVesalius(d / "nothing.inv3"); }},
             {"text.mhd", [&] { readInVesaliusHeader(d / "text.mhd"); }}}) {
        e = loadErrorOf(read);
        QVERIFY2(e.contains(QString::fromStdString(name)),
                 qPrintable(QString::fromStdString(name) + ": " + e));
    }
}

void TestVolumeFormats::inVesaliusSynthetic() {
    QTemporaryDir dir;
    const fs::path path = dirOf(dir) / "tiny.inv3";
    const std::string plist =
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<plist version=\"1.0\">\n<dict>\n"
        "<key>matrix</key><dict><key>dtype</key><string>int16</string>"
        "<key>filename</key><string>matrix.dat</string><key>shape</key>"
        "<array><integer>2</integer><integer>3</integer><integer>4</integer></array></dict>\n"
        "<key>modality</key><string>CT</string><key>name</key><string>Tiny &amp; test</string>\n"
        "<key>spacing</key><array><real>0.5</real><real>0.75</real><real>2.0</real></array>\n"
        "</dict>\n</plist>\n";
    std::string matrix;
    for (int n = 0; n < 24; ++n) { // C order (slice, row, col): col fastest
        matrix += static_cast<char>(n);
        matrix += '\0';
    }
    test::writeTarGz(path, {{"tmpabc/main.plist", plist}, {"tmpabc/matrix.dat", matrix}});
    const Volume v = readInVesalius(path);
    QCOMPARE(v.dims(), glm::ivec3(4, 3, 2));
    QCOMPARE(v.modality, std::string("CT"));
    QCOMPARE(v.description, std::string("Tiny & test"));
    QCOMPARE(v.value(3, 2, 1), 23.0); // col 3, row 2, slice 1
    QCOMPARE(v.value(1, 0, 0), 1.0);
    const VolumeGeometry& g = v.geometry();
    QVERIFY(near(g.direction[0], {1, 0, 0}, 0.0));  // columns: right -> left
    QVERIFY(near(g.direction[1], {0, -1, 0}, 0.0)); // rows: posterior -> anterior
    QVERIFY(near(g.direction[2], {0, 0, 1}, 0.0));  // slices: inferior -> superior
    QVERIFY(near(g.spacing, {0.5, 0.75, 2.0}, 0.0));
    QVERIFY(near(g.toPatient(glm::dvec3(g.dims - 1) * 0.5), {0, 0, 0}, 1e-12));
}

void TestVolumeFormats::inVesaliusMissingKey() {
    QTemporaryDir dir;
    const fs::path path = dirOf(dir) / "nospacing.inv3";
    const std::string plist = "<plist version=\"1.0\"><dict><key>matrix</key><dict>"
                              "<key>dtype</key><string>int16</string><key>filename</key>"
                              "<string>matrix.dat</string><key>shape</key><array><integer>1"
                              "</integer><integer>1</integer><integer>1</integer></array>"
                              "</dict></dict></plist>";
    test::writeTarGz(path, {{"p/main.plist", plist}, {"p/matrix.dat", std::string(2, '\0')}});
    const QString e = loadErrorOf([&] { readInVesaliusHeader(path); });
    QVERIFY2(e.contains("nospacing.inv3") && e.contains("'spacing'"), qPrintable(e));
}

void TestVolumeFormats::inVesaliusDemo() {
    if (!fs::exists(demoProject)) {
        QSKIP("InVesalius demo Cranium.inv3 not installed (packaging/install-deps.sh installs "
              "invesalius-examples)");
    }
    const VolumeFileHeader header = readInVesaliusHeader(demoProject);
    QCOMPARE(header.geometry.dims, glm::ivec3(256, 256, 108));
    QVERIFY(near(header.geometry.spacing, {0.9570312, 0.9570312, 1.5}, 1e-6));
    QCOMPARE(header.modality, std::string("CT"));

    const Volume v = readInVesalius(demoProject);
    const auto [lo, hi] = v.valueRange();
    QCOMPARE(lo, -1024.0);
    QVERIFY(hi > 2000.0 && hi < 4000.0);

    // Anatomy, in patient coordinates (LPS: +y posterior, +z superior).
    const auto [lower, upper] = patientBounds(v.geometry());
    const AxialCounts top = axialPlaneCounts(v, upper.z - 3.0);    // just below the vertex
    const AxialCounts bottom = axialPlaneCounts(v, lower.z + 3.0); // through the teeth
    // Head up: the cross-section near the top of the head is a small cap of scalp,
    // the one through the jaw is the whole face and neck.
    QVERIFY2(top.tissue * 5 < bottom.tissue,
             qPrintable(QString("tissue top %1 bottom %2").arg(top.tissue).arg(bottom.tissue)));
    // Face anterior: at the level of the teeth the dense bone lies in front.
    QVERIFY2(bottom.anteriorBone > 300 && bottom.anteriorBone > 5 * bottom.posteriorBone,
             qPrintable(QString("teeth-level bone anterior %1 posterior %2")
                            .arg(bottom.anteriorBone)
                            .arg(bottom.posteriorBone)));
}

QTEST_APPLESS_MAIN(TestVolumeFormats)
#include "test_volume_formats.moc"
