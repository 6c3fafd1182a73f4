// Segments in 3D on the real head CT (512 x 512 x 140): scissors through the 3D view against
// every voxel centre projected on its own with the view's frame (perspective, as VolumeView
// draws) or an orthographic frame; the masked volume; a segment's surface, its enclosed
// volume against the mask's, and its STL, PLY and OBJ files read back.
#include <QElapsedTimer>
#include <QFile>
#include <QTemporaryDir>
#include <QTest>

#include <cstring>
#include <fstream>
#include <sstream>

#include "core/formats/MeshFiles.h"
#include "core/io/Catalog.h"
#include "core/scene/ViewFrame.h"
#include "core/segmentation/MaskedVolume.h"
#include "core/segmentation/ScissorsCut.h"
#include "core/segmentation/SegmentEffects.h"
#include "core/segmentation/SegmentSurface.h"
#include "tests/support/CliRunner.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

constexpr const char* kHeadCt = "dcm_qa_ct/Philips_S21570/S2020";

// Where the frame shows p, in pixels of a w x h view: the ray caster's screenX/screenY
// inverted, written out here independently of ImageProjection. Nothing at or behind the eye.
std::optional<glm::dvec2> perspectivePixel(const ViewFrame& f, glm::dvec3 p, int w, int h) {
    const glm::dvec3 rel = p - f.eye;
    const double z = glm::dot(rel, f.forward);
    if (z <= 1e-9) {
        return std::nullopt;
    }
    const double sx = glm::dot(rel, f.right) / (z * f.tanHalfFov * f.aspect);
    const double sy = glm::dot(rel, f.up) / (z * f.tanHalfFov);
    return glm::dvec2((sx + 1.0) * 0.5 * w, (1.0 - sy) * 0.5 * h);
}

// An orthographic view of half-height `half` mm round `centre`, looking along f.forward.
struct Ortho {
    ViewFrame f;
    glm::dvec3 centre;
    double half;
    std::optional<glm::dvec2> pixel(glm::dvec3 p, int w, int h) const {
        const glm::dvec3 rel = p - centre;
        const double sx = glm::dot(rel, f.right) / (half * f.aspect);
        const double sy = glm::dot(rel, f.up) / half;
        return glm::dvec2((sx + 1.0) * 0.5 * w, (1.0 - sy) * 0.5 * h);
    }
    ImageProjection matrix() const {
        const glm::dvec3 ru = f.right / (2.0 * half * f.aspect), rv = -f.up / (2.0 * half);
        return {ru.x, ru.y, ru.z, 0.5 - glm::dot(ru, centre),
                rv.x, rv.y, rv.z, 0.5 - glm::dot(rv, centre),
                0.0,  0.0,  0.0,  1.0};
    }
};

// The test's own even-odd rule and shapes.
bool insideShape(const std::vector<glm::dvec2>& poly, glm::dvec2 p) {
    bool in = false;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
            p.x <
                (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x) {
            in = !in;
        }
    }
    return in;
}

template <class Project, class Inside>
SegmentMask reference(const VolumeGeometry& g, Project project, Inside inside) {
    SegmentMask out(g.dims);
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const auto p = project(g.toPatient(glm::dvec3(i, j, k)));
                if (p && inside(*p)) {
                    out.set(out.linearIndex(i, j, k));
                }
            }
        }
    }
    return out;
}

// A freehand-like outline that crosses itself: a five-pointed star drawn in one stroke.
std::vector<glm::dvec2> star(glm::dvec2 c, double r) {
    std::vector<glm::dvec2> pts;
    for (int n = 0; n < 5; ++n) {
        const double a = glm::radians(-90.0 + 144.0 * n);
        pts.push_back(c + r * glm::dvec2(std::cos(a), std::sin(a)) + glm::dvec2(0.3 * n, 0.0));
    }
    return pts;
}

std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

} // namespace

class TestSegment3d : public QObject {
    Q_OBJECT

    Volume ct_;

private slots:
    void initTestCase() {
        REQUIRE_DATA(kHeadCt);
        ct_ = loadPath(test::kRealData / kHeadCt);
        QCOMPARE(ct_.dims(), glm::ivec3(512, 512, 140));
    }

    void scissorsPerspective() {
        const VolumeGeometry& g = ct_.geometry();
        const int w = 400, h = 300;
        Camera camera;
        camera.azimuth = 30.0;
        camera.elevation = -20.0;
        camera.zoom = 1.6;
        const ViewFrame f = makeViewFrame(g, camera, w, h);
        const ImageProjection m = imageProjection(f);
        const auto project = [&](glm::dvec3 p) { return perspectivePixel(f, p, w, h); };
        const glm::dvec2 size(w, h);

        const std::vector<glm::dvec2> outline = star({200.0, 150.0}, 110.0);
        QElapsedTimer timer;
        timer.start();
        const SegmentMask polygon =
            scissorsMask(g, m, size, ScreenShape::polygon(outline), ScissorsSide::Inside);
        qInfo("polygon scissors mask: %lld ms", timer.elapsed());
        const SegmentMask polygonRef =
            reference(g, project, [&](glm::dvec2 p) { return insideShape(outline, p); });
        QVERIFY(polygonRef.count() > 100000);
        QVERIFY(polygon == polygonRef);

        const SegmentMask circleOut = scissorsMask(
            g, m, size, ScreenShape::circle({180.0, 160.0}, 70.0), ScissorsSide::Outside);
        SegmentMask circleRef = reference(g, project, [](glm::dvec2 p) {
            return glm::dot(p - glm::dvec2(180.0, 160.0), p - glm::dvec2(180.0, 160.0)) <=
                   70.0 * 70.0;
        });
        QVERIFY(circleRef.count() > 100000);
        QVERIFY(circleOut == circleRef.invert());

        // Erase inside a rectangle over the lower part of the view from a segment of all.
        const glm::dvec2 a(20.5, 210.25), b(390.0, 300.0);
        SegmentMask all(g.dims);
        all.invert();
        const SegmentMask kept = applyScissors(all, g, m, size, ScreenShape::rectangle(b, a),
                                               ScissorsOperation::EraseInside);
        SegmentMask removed = reference(g, project, [&](glm::dvec2 p) {
            return p.x >= a.x && p.x <= b.x && p.y >= a.y && p.y <= b.y;
        });
        QVERIFY(removed.count() > 10000);
        QVERIFY(kept == all.subtract(removed));
    }

    void scissorsOrthographic() {
        const VolumeGeometry& g = ct_.geometry();
        const int w = 320, h = 320;
        Camera camera;
        camera.azimuth = -75.0;
        camera.elevation = 35.0;
        const Ortho ortho{makeViewFrame(g, camera, w, h), volumeCentre(g), 90.0};
        const std::vector<glm::dvec2> outline = star({170.0, 150.0}, 120.0);
        const SegmentMask cut = scissorsMask(g, ortho.matrix(), glm::dvec2(w, h),
                                             ScreenShape::polygon(outline), ScissorsSide::Outside);
        SegmentMask ref = reference(
            g, [&](glm::dvec3 p) { return ortho.pixel(p, w, h); },
            [&](glm::dvec2 p) { return insideShape(outline, p); });
        QVERIFY(ref.count() > 100000);
        QVERIFY(cut == ref.invert());
    }

    void maskedCopy() {
        SegmentMask bone = thresholdMask(ct_, 300.0, 4000.0);
        const auto [lowest, highest] = ct_.valueRange();
        for (const MaskKeep keep : {MaskKeep::Inside, MaskKeep::Outside}) {
            const Volume masked = maskedVolume(ct_, bone, keep);
            QCOMPARE(masked.geometry().dims, ct_.dims());
            QCOMPARE(masked.seriesUid, ct_.seriesUid);
            const std::span<const std::int16_t> in = std::as_const(ct_).voxels<std::int16_t>();
            const std::span<const std::int16_t> out = masked.voxels<std::int16_t>();
            std::size_t kept = 0;
            for (std::size_t i = 0; i < in.size(); ++i) {
                const bool keepIt = bone.get(i) == (keep == MaskKeep::Inside);
                QCOMPARE(double(out[i]), keepIt ? double(in[i]) : lowest);
                kept += keepIt ? 1 : 0;
            }
            QVERIFY(kept > 0 && kept < in.size());
        }
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 maskedVolume(ct_, SegmentMask(glm::ivec3(2)), MaskKeep::Inside));
    }

    void surfaceAndFiles() {
        // The largest soft-tissue insert: a solid blob inside the skull.
        const SegmentMask insert = keepLargestIsland(thresholdMask(ct_, 50.0, 200.0));
        const glm::dvec3 s = ct_.geometry().spacing;
        const double maskMm3 = double(insert.count()) * s.x * s.y * s.z;
        const SurfaceResult surface = segmentSurface(insert, ct_.geometry());
        QVERIFY(surface.report.closedManifold());
        const double ratio = surface.report.volume / maskMm3;
        qInfo("insert: mask %.1f mL, surface encloses %.1f mL (ratio %.4f), %zu triangles",
              maskMm3 / 1000.0, surface.report.volume / 1000.0, ratio, surface.report.triangles);
        QVERIFY(std::abs(ratio - 1.0) < 0.03);

        QTemporaryDir dir;
        const std::filesystem::path stl = dir.filePath("insert.stl").toStdString();
        MeshFileContent content;
        content.description = "Lucent segment insert";
        writeMesh(surface.mesh, stl, MeshFormat::Stl, content);
        const std::string bytes = slurp(stl);
        QVERIFY(bytes.size() >= 84);
        std::uint32_t count = 0;
        std::memcpy(&count, bytes.data() + 80, 4);
        QCOMPARE(std::size_t(count), surface.mesh.triangles.size());
        QCOMPARE(bytes.size(), 84 + 50 * std::size_t(count));

        const std::filesystem::path obj = dir.filePath("insert.obj").toStdString();
        writeMesh(surface.mesh, obj, MeshFormat::Obj);
        std::istringstream lines(slurp(obj));
        std::size_t faces = 0;
        for (std::string line; std::getline(lines, line);) {
            faces += line.rfind("f ", 0) == 0 ? 1 : 0;
        }
        QCOMPARE(faces, surface.mesh.triangles.size());

        const std::filesystem::path ply = dir.filePath("insert.ply").toStdString();
        writeMesh(surface.mesh, ply, MeshFormat::Ply);
        const std::string header = slurp(ply).substr(0, 400);
        QVERIFY(header.find("element face " + std::to_string(surface.mesh.triangles.size())) !=
                std::string::npos);

        QVERIFY_THROWS_EXCEPTION(std::runtime_error,
                                 segmentSurface(SegmentMask(ct_.dims()), ct_.geometry()));

        // lucent-cli segment --surface: the same mesh in the file.
        const QString ct = QString::fromStdString((test::kRealData / kHeadCt).string());
        const QString cliStl = dir.filePath("cli.stl");
        const test::CliRun run =
            test::runCli({"segment", ct, "--threshold", "50,200", "--keep-largest", "-o",
                          dir.filePath("insert.nii.gz"), "--surface", cliStl});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const std::string cliBytes = slurp(cliStl.toStdString());
        QVERIFY(cliBytes.size() >= 84);
        std::memcpy(&count, cliBytes.data() + 80, 4);
        QCOMPARE(std::size_t(count), surface.mesh.triangles.size());
        const test::CliRun bad =
            test::runCli({"segment", ct, "--threshold", "50,200", "-o", dir.filePath("x.nii.gz"),
                          "--surface", dir.filePath("x.step")});
        QCOMPARE(bad.exitCode, 2);
        QVERIFY(bad.err.contains("x.step"));
        QVERIFY(!QFile::exists(dir.filePath("x.nii.gz")));
    }
};

QTEST_GUILESS_MAIN(TestSegment3d)
#include "test_segment_3d.moc"
