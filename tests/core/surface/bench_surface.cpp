// Benchmark (label perf): isosurface extraction by lucent-cli surface against
// VTK 9.1's vtkFlyingEdges3D and vtkMarchingCubes (Debian's python3-vtk9) on
// the same MetaImage and iso value, side by side in one run: the Philips CT
// at 300 HU and the demo CT (InVesalius' Cranium) at 226 HU, best of three.
// Then the method of spheres on the demo skull at R = 2 and 5 mm: time, the
// triangles each vertex looked at against the paper's all-pairs cost, and the
// memory per triangle. Prints the figures; asserts only that the counts agree
// within 1 % (docs/surfaces.md).
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTest>

#include <algorithm>

#include "tests/support/CliRunner.h"

using namespace lucent::test;

class BenchSurface : public QObject {
    Q_OBJECT
    QTemporaryDir tmp_;

    QString convert(const QString& source, const QString& name) {
        const QString mhd = tmp_.filePath(name + ".mhd");
        const CliRun r = runCli({"convert", source, mhd}, 600000);
        return r.exitCode == 0 ? mhd : QString();
    }

private slots:
    void extractionAgainstVtk_data() {
        QTest::addColumn<QString>("source");
        QTest::addColumn<double>("iso");
        QTest::newRow("Philips CT, 300 HU")
            << QString(LUCENT_TEST_DATA_DIR "/dcm_qa_ct/Philips_S21570/S2020") << 300.0;
        QTest::newRow("demo CT, 226 HU")
            << QString("/usr/share/doc/invesalius-examples/examples/Cranium.inv3") << 226.0;
    }
    void extractionAgainstVtk() {
        QFETCH(QString, source);
        QFETCH(double, iso);
        const QString mhd = convert(source, QString::number(qHash(source)));
        QVERIFY2(!mhd.isEmpty(), qPrintable(source));
        double ours = 1e300, triangles = 0.0;
        for (int n = 0; n < 3; ++n) {
            const CliRun r = runCli({"surface", mhd, "-o", tmp_.filePath("s.stl"), "--iso",
                                     QString::number(iso), "--stats"});
            QVERIFY2(r.exitCode == 0, qPrintable(r.err));
            ours = std::min(ours, statOf(r.out, "extract_ms"));
            triangles = statOf(r.out, "triangles");
        }
        QProcess python;
        python.start("/usr/bin/python3", {LUCENT_SOURCE_DIR "/tests/core/surface/vtk_contour.py",
                                          mhd, QString::number(iso), "3"});
        QVERIFY(python.waitForFinished(600000));
        const QStringList vtk =
            QString::fromUtf8(python.readAllStandardOutput()).trimmed().split(' ');
        if (vtk.size() != 5) {
            QFAIL(qPrintable("VTK's contouring failed (install python3-vtk9: "
                             "packaging/install-deps.sh): " +
                             QString::fromUtf8(python.readAllStandardError())));
        }
        qInfo("%s: lucent %.1f ms %.0f triangles | vtkFlyingEdges3D %s ms %s triangles | "
              "vtkMarchingCubes %s ms %s triangles | VTK threads %s | lucent/FE time %.2f",
              QTest::currentDataTag(), ours, triangles, qPrintable(vtk[1]), qPrintable(vtk[2]),
              qPrintable(vtk[3]), qPrintable(vtk[4]), qPrintable(vtk[0]), ours / vtk[1].toDouble());
        QVERIFY(std::abs(triangles / vtk[2].toDouble() - 1.0) < 0.01);
    }

    void methodOfSpheresOnTheSkull() {
        for (const char* radius : {"2", "5"}) {
            const CliRun r = runCli({"surface",
                                     "/usr/share/doc/invesalius-examples/examples/"
                                     "Cranium.inv3",
                                     "-o", tmp_.filePath("skull.ply"), "--iso", "226",
                                     "--svr-radius", radius, "--stats"},
                                    600000);
            QVERIFY2(r.exitCode == 0, qPrintable(r.err));
            const double vertices = statOf(r.out, "vertices");
            const double triangles = statOf(r.out, "triangles");
            const double candidates = statOf(r.out, "svr_candidates_per_vertex");
            qInfo("R = %s mm: %.0f vertices, %.0f triangles, svr %.0f ms (%s threads), %.0f "
                  "vertices/s; %.1f candidates and %s clipped per vertex; all pairs %.3g, "
                  "looked at %.3g (%.0fx less); p05 %s p50 %s p95 %s /mm; memory per triangle: "
                  "mesh %s B, SVR index %s B",
                  radius, vertices, triangles, statOf(r.out, "svr_ms"),
                  qPrintable(QString::number(statOf(r.out, "svr_threads"))),
                  vertices / statOf(r.out, "svr_ms") * 1000.0, candidates,
                  qPrintable(QString::number(statOf(r.out, "svr_clipped_per_vertex"))),
                  vertices * triangles, vertices * candidates, triangles / candidates,
                  qPrintable(QString::number(statOf(r.out, "svr_p05"))),
                  qPrintable(QString::number(statOf(r.out, "svr_p50"))),
                  qPrintable(QString::number(statOf(r.out, "svr_p95"))),
                  qPrintable(QString::number(statOf(r.out, "mesh_bytes_per_triangle"))),
                  qPrintable(QString::number(statOf(r.out, "svr_index_bytes_per_triangle"))));
            QVERIFY(triangles / candidates >= 100.0);
        }
    }
};

QTEST_GUILESS_MAIN(BenchSurface)
#include "bench_surface.moc"
