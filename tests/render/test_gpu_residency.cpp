// What the GPU keeps: only the bricks a transfer function needs, never
// uploaded twice; coarser levels when the budget is small; clear errors.
#include <QTest>

#include "core/quality/InteractiveQuality.h"
#include "core/volume/BrickResidency.h"
#include "render/GlError.h"
#include "render/GlObjects_p.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/render/GlTestSupport.h"
#include "tests/render/RealOrMadeCt.h"

using namespace lucent;
using namespace lucent::test;

class TestGpuResidency : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;

private slots:
    void initTestCase() { context_ = OffscreenContext::create(); }

    // Bone needs fewer bricks than soft tissue; switching to soft tissue
    // uploads only bricks whose boxes bone did not hold, and returning
    // uploads nothing.
    void transferFunctionChangeUploadsNoVoxelTwice() {
        const Volume v = realOrMade();
        GpuRayCaster gpu(v);
        RenderDescription d = describe(v, loadPreset("ct-bone"), 64);
        const GpuRenderResult bone = gpu.renderWithGpuStats(d);
        QVERIFY(bone.gpu.bricksUploaded > 0);
        QCOMPARE(bone.gpu.bricksUploaded, bone.gpu.pagesShown);
        QVERIFY(bone.frame.stats.bricksUsed < bone.frame.stats.bricksTotal);
        // The pool is sized to the scene (with some headroom), not to the volume,
        // and keeps gradients when they fit the budget.
        QVERIFY(bone.gpu.gradientsCached);
        QVERIFY2(bone.gpu.poolBytes >= bone.gpu.residentBytes &&
                     bone.gpu.poolBytes <= bone.gpu.residentBytes * 3 / 2 + (1U << 20),
                 qPrintable(QString("a pool of %1 bytes for %2 resident")
                                .arg(bone.gpu.poolBytes)
                                .arg(bone.gpu.residentBytes)));
        QCOMPARE(bone.gpu.residentBytes, bone.gpu.bytesUploaded);

        d.transferFunction = loadPreset("ct-soft-tissue");
        const GpuRenderResult soft = gpu.renderWithGpuStats(d);
        QVERIFY(soft.frame.stats.bricksUsed >= bone.frame.stats.bricksUsed);
        // Bricks whose boxes bone already held are not uploaded again.
        GpuRayCaster fresh(v);
        const GpuRenderResult freshSoft = fresh.renderWithGpuStats(d);
        QVERIFY2(soft.gpu.bytesUploaded < freshSoft.gpu.bytesUploaded,
                 qPrintable(QString("%1 bytes after bone, %2 from nothing")
                                .arg(soft.gpu.bytesUploaded)
                                .arg(freshSoft.gpu.bytesUploaded)));
        // The same image (boxes elsewhere in the atlas filter to within rounding).
        QVERIFY(psnr(soft.frame.image, freshSoft.frame.image) >= 60.0);

        d.transferFunction = loadPreset("ct-bone");
        const GpuRenderResult again = gpu.renderWithGpuStats(d);
        QCOMPARE(again.gpu.bricksUploaded, std::size_t(0));
        // The same image from the bricks soft tissue's boxes hold.
        QVERIFY(psnr(again.frame.image, bone.frame.image) >= 60.0);

        d.camera.azimuth = 90.0; // a new view of the same scene needs no upload either
        QCOMPARE(gpu.renderWithGpuStats(d).gpu.bricksUploaded, std::size_t(0));
    }

    // Zoomed in, only the bricks in view are resident, and the image is still
    // the reference's.
    void onlyBricksInViewAreResident() {
        const Volume v = realOrMade();
        GpuRayCaster gpu(v);
        RenderDescription d = describe(v, loadPreset("ct-bone"), 96);
        const std::size_t whole = gpu.renderWithGpuStats(d).frame.stats.bricksUsed;
        GpuRayCaster zoomed(v);
        d.camera.zoom = 4.0;
        d.camera.azimuth = 20.0;
        const GpuRenderResult r = zoomed.renderWithGpuStats(d);
        QVERIFY2(r.frame.stats.bricksUsed * 2 < whole,
                 qPrintable(
                     QString("%1 bricks in view of %2").arg(r.frame.stats.bricksUsed).arg(whole)));
        QCOMPARE(r.gpu.bricksUploaded, r.gpu.pagesShown);
        RenderDescription ref = d;
        ref.sampling.precision = Precision::Double;
        const double p =
            comparedPsnr(r.frame.image, CpuRayCaster(v).render(ref).image, "zoomed", 40.0);
        QVERIFY2(p >= 40.0, qPrintable(QString("zoomed: %1 dB").arg(p)));
    }

    // A budget far below the volume still renders, from a coarser level, says
    // so, and looks like the full-resolution image.
    void smallBudgetRendersCoarserLevel() {
        const Volume v = realOrMade();
        RenderDescription d = describe(v, loadPreset("ct-bone"), 96);
        GpuRayCaster full(v);
        const GpuRenderResult fine = full.renderWithGpuStats(d);
        QCOMPARE(fine.frame.stats.lod, 0);

        GpuOptions small;
        small.budgetBytes = v.byteCount() / 3;
        GpuRayCaster gpu(v, small);
        const GpuRenderResult coarse = gpu.renderWithGpuStats(d);
        QVERIFY2(coarse.frame.stats.lod > 0,
                 "a budget of a third of the volume should need a coarser level");
        QVERIFY(!coarse.gpu.lodReason.empty());
        QVERIFY(coarse.gpu.residentBytes <= coarse.gpu.poolBytes);
        QVERIFY(coarse.gpu.poolBytes <= small.budgetBytes);
        const double p = psnr(coarse.frame.image, fine.frame.image);
        QVERIFY2(p > 25.0, qPrintable(QString("coarse level vs full: psnr %1 dB").arg(p)));
    }

    // At a coarser level (one for the whole volume) the gradient cache is kept
    // when that level's bricks fit with it, and shades as the computed
    // gradients do.
    void coarseLevelKeepsGradientCache() {
        const Volume v = realOrMade();
        const RenderDescription d = describe(v, loadPreset("ct-bone"), 96);
        for (const std::size_t mib : {80, 60, 100, 40, 120}) {
            GpuOptions cachedOptions;
            cachedOptions.budgetBytes = mib << 20;
            cachedOptions.lodPolicy = LodPolicy::Uniform;
            GpuOptions computedOptions = cachedOptions;
            computedOptions.gradientCache = false;
            GpuRayCaster cachedGpu(v, cachedOptions);
            GpuRenderResult cached;
            try {
                cached = cachedGpu.renderWithGpuStats(d);
            } catch (const BudgetError&) {
                continue;
            }
            if (cached.frame.stats.lod == 0 || !cached.gpu.gradientsCached) {
                continue;
            }
            GpuRayCaster computedGpu(v, computedOptions);
            const GpuRenderResult computed = computedGpu.renderWithGpuStats(d);
            QCOMPARE(computed.frame.stats.lod, cached.frame.stats.lod); // gradients cost no level
            QVERIFY(!computed.gpu.gradientsCached);
            QVERIFY(cached.gpu.poolBytes <= cachedOptions.budgetBytes);
            const double p =
                comparedPsnr(cached.frame.image, computed.frame.image, "coarse-gradients", 50.0);
            QVERIFY2(p >= 50.0, qPrintable(QString("level %1, %2 MiB: cached vs computed %3 dB")
                                               .arg(cached.frame.stats.lod)
                                               .arg(mib)
                                               .arg(p)));
            return;
        }
        QSKIP("no budget tried renders a coarser level with cached gradients for this volume");
    }

    // The default path's bricks take at most twice the volume's bytes: the
    // Philips CT keeps its cached gradients (186 %), the head CT, whose
    // visible boxes cover most of it, computes them (the cache would take 3x).
    void gradientCacheStaysWithinTwiceTheVolume() {
        const std::filesystem::path head =
            "/usr/share/doc/invesalius-examples/examples/Cranium.inv3";
        if (!std::filesystem::exists(head)) {
            QFAIL("invesalius-examples is not installed: run packaging/install-deps.sh");
        }
        for (const auto& path : {philipsCt(), head}) {
            if (!std::filesystem::exists(path)) {
                continue;
            }
            const Volume v = loadPath(path);
            RenderDescription d = describe(v, loadPreset("ct-bone"), 64);
            GpuRayCaster gpu(v);
            const GpuRenderResult r = gpu.renderWithGpuStats(d);
            QVERIFY2(r.gpu.residentBytes <= 2 * v.byteCount(),
                     qPrintable(QString("%1: %2 MiB resident for a volume of %3 MiB")
                                    .arg(QString::fromStdString(path.string()))
                                    .arg(r.gpu.residentBytes >> 20)
                                    .arg(v.byteCount() >> 20)));
            GpuOptions unlimited;
            unlimited.gradientCacheShare = 0.0;
            GpuRayCaster cacheAlways(v, unlimited);
            const GpuRenderResult all = cacheAlways.renderWithGpuStats(d);
            QVERIFY(all.gpu.gradientsCached);
            // Cached where it fits the share, computed where not; the same image either way.
            QCOMPARE(r.gpu.gradientsCached, all.gpu.residentBytes <= 2 * v.byteCount());
            const double p = comparedPsnr(r.frame.image, all.frame.image, "gradient-share", 50.0);
            QVERIFY2(p >= 50.0, qPrintable(QString("within the share vs unlimited: %1 dB").arg(p)));
            if (path == philipsCt()) {
                QVERIFY(r.gpu.gradientsCached);
            } else {
                QVERIFY(!r.gpu.gradientsCached);
            }
        }
    }

    void budgetTooSmallForAnyLevelSaysSo() {
        const Volume v = realOrMade();
        GpuOptions tiny;
        tiny.budgetBytes = 1024; // not one brick
        GpuRayCaster gpu(v, tiny);
        try {
            gpu.renderWithGpuStats(describe(v, loadPreset("ct-bone"), 32));
            QFAIL("a 1 KiB budget rendered");
        } catch (const BudgetError& e) {
            QVERIFY2(std::string(e.what()).find("budget") != std::string::npos, e.what());
        }
    }

    // While dragging: fewer samples on a smaller image, scaled up to the view,
    // close to the still frame.
    void interactiveFrameIsCheaperAndClose() {
        const Volume v = realOrMade();
        GpuRayCaster gpu(v);
        const RenderDescription still = describe(v, loadPreset("ct-bone"), 128);
        const GpuRenderResult full = gpu.renderWithGpuStats(still);
        const RenderDescription moving = interactiveDescription(still);
        QCOMPARE(moving.width, 64);
        QCOMPARE(moving.sampling.step, 2.0 * still.sampling.step);
        const GpuRenderResult quick = gpu.renderWithGpuStats(moving);
        QVERIFY2(quick.frame.stats.samples * 4 < full.frame.stats.samples,
                 qPrintable(QString("%1 vs %2 samples")
                                .arg(quick.frame.stats.samples)
                                .arg(full.frame.stats.samples)));
        const ImageRGBA8 shown = scaledTo(quick.frame.image, 128, 128);
        QCOMPARE(shown.width, 128);
        const double p = psnr(shown, full.frame.image);
        QVERIFY2(p > 20.0, qPrintable(QString("interactive vs still: %1 dB").arg(p)));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 interactiveDescription(still, InteractiveQuality{0.5, 0.5}));
    }

    // Longer than one 3D texture may be (GL_MAX_3D_TEXTURE_SIZE, 2048 on llvmpipe):
    // bricks make that no limit.
    void volumeBeyondOneTextureRenders() {
        GLint maxSize = 0;
        glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
        const int length = std::max(2100, int(maxSize) + 50);
        const Volume v = makeVolume(
            {24, 20, length},
            [length](int i, int j, int k) {
                return (i - 12) * (i - 12) + (j - 10) * (j - 10) < 40 && k % 300 < 250
                           ? 900.0 - k * 0.1
                           : -1000.0 + k % 7;
            },
            VoxelType::Int16);
        RenderDescription d = describe(v, loadPreset("ct-bone"), 64);
        d.camera.azimuth = 90.0;
        GpuRayCaster gpu(v);
        const GpuRenderResult r = gpu.renderWithGpuStats(d);
        QCOMPARE(r.frame.stats.lod, 0);
        RenderDescription ref = d;
        ref.sampling.precision = Precision::Double;
        const double p =
            comparedPsnr(r.frame.image, CpuRayCaster(v).render(ref).image, "long", 40.0);
        QVERIFY2(p >= 40.0, qPrintable(QString("%1 slices: %2 dB").arg(length).arg(p)));
    }

    // A shader that does not compile is an error that names it and carries the log.
    void shaderErrorsNameTheShader() {
        try {
            ShaderProgram broken("raycast.vert", "raycast.frag", "#error deliberately broken\n");
            QFAIL("a broken shader compiled");
        } catch (const GlError& e) {
            const std::string what = e.what();
            QVERIFY2(what.find("raycast") != std::string::npos &&
                         what.find("deliberately") != std::string::npos,
                     e.what());
        }
    }

    void badSettingsAreRefusedByName() {
        const Volume v = realOrMade();
        GpuRayCaster gpu(v);
        RenderDescription d = describe(v, loadPreset("ct-bone"), 32);
        d.sampling.step = -1.0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, gpu.renderWithGpuStats(d));
    }
};

QTEST_GUILESS_MAIN(TestGpuResidency)
#include "test_gpu_residency.moc"
