// Tight bricks and per-brick levels on the GPU: a trimmed brick draws what the
// whole brick drew; a wider transfer function re-fits the boxes; bricks of
// different levels meet without seams; a tight budget still renders and says
// so; bricks streamed in under an upload cap end where an uncapped frame is;
// a brick's page entry holds its page and box, as the shader decodes them.
#include <QTest>

#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

#include "core/volume/LodPyramid.h"
#include "render/BrickTable.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/render/GlTestSupport.h"
#include "tests/render/RealOrMadeCt.h"

using namespace lucent;
using namespace lucent::test;

namespace {

// The volume each page of a mixed-level frame shows, resampled onto level 0:
// a voxel takes the nearest voxel of its page's level (levels nest, so nearest
// sampling of this volume is nearest sampling of that level); voxels of pages
// drawn from nothing take the volume's lowest value.
Volume resampledAtFrameLevels(const Volume& v, const GpuFrameStats& frame) {
    const LodPyramid pyramid(v);
    Volume out(v.geometry(), v.type());
    out.modality = v.modality;
    const glm::ivec3 dims = v.dims();
    const int page = frame.pageSize;
    const glm::ivec3 pages = (dims + page - 1) / page;
    const double lowest = v.valueRange().first;
    auto voxels = out.voxels<std::int16_t>();
    for (int k = 0; k < dims.z; ++k) {
        for (int j = 0; j < dims.y; ++j) {
            for (int i = 0; i < dims.x; ++i) {
                const glm::ivec3 p = glm::ivec3(i, j, k) / page;
                const int level =
                    frame.levelOfBrick[std::size_t(p.x + pages.x * (p.y + pages.y * p.z))];
                double value = lowest;
                if (level == 0) {
                    value = v.value(i, j, k);
                } else if (level > 0) {
                    const Volume& l = pyramid.level(level);
                    const glm::dvec3 q =
                        glm::clamp(LodPyramid::fromLevel0(glm::dvec3(i, j, k), level),
                                   glm::dvec3(0.0), glm::dvec3(l.dims() - 1));
                    const glm::ivec3 n(glm::floor(q + 0.5));
                    value = l.value(n.x, n.y, n.z);
                }
                voxels[std::size_t(i) +
                       std::size_t(dims.x) * (std::size_t(j) + std::size_t(dims.y) * k)] =
                    std::int16_t(value);
            }
        }
    }
    return out;
}

} // namespace

class TestGpuBricks : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;
    Volume volume_;

private slots:
    void initTestCase() {
        context_ = OffscreenContext::create();
        volume_ = realOrMade();
        QVERIFY(volume_.type() == VoxelType::Int16);
    }

    // Trimmed to what shows, the bricks draw what whole bricks drew, with
    // the filters that read furthest.
    void tightEqualsUntrimmed_data() {
        QTest::addColumn<int>("scene");
        QTest::newRow("linear shaded, gradients cached") << 0;
        QTest::newRow("cubic shaded pre-integrated") << 1;
        QTest::newRow("linear shaded, computed gradients") << 2;
        QTest::newRow("iso") << 3;
    }
    void tightEqualsUntrimmed() {
        QFETCH(int, scene);
        RenderDescription d = describe(volume_, loadPreset("ct-bone"), 128);
        d.camera.azimuth = 30.0;
        d.camera.elevation = 20.0;
        GpuOptions tight, untrimmed;
        untrimmed.tightBricks = false;
        if (scene == 1) {
            d.sampling.interpolation = Interpolation::Cubic;
            d.sampling.preintegrate = true;
        } else if (scene == 2) {
            tight.gradientCache = untrimmed.gradientCache = false;
        } else if (scene == 3) {
            d.mode = RenderMode::Isosurface;
            d.isoValue = 300.0;
        }
        GpuRayCaster a(volume_, tight), b(volume_, untrimmed);
        const GpuRenderResult ra = a.renderWithGpuStats(d), rb = b.renderWithGpuStats(d);
        QVERIFY2(ra.gpu.valueBytes < rb.gpu.valueBytes,
                 qPrintable(QString("%1 bytes trimmed, %2 whole")
                                .arg(ra.gpu.valueBytes)
                                .arg(rb.gpu.valueBytes)));
        const double p =
            comparedPsnr(ra.frame.image, rb.frame.image, "tight_" + std::to_string(scene), 50.0);
        QVERIFY2(p >= 50.0, qPrintable(QString("tight against untrimmed: %1 dB").arg(p)));
    }

    // A transfer function that shows more re-fits the boxes: from fat to
    // bone to soft tissue, every frame equals a fresh caster's, no hole.
    void widerTransferFunctionRefitsBoxes() {
        GpuRayCaster gpu(volume_);
        RenderDescription d = describe(volume_, loadPreset("ct-bone"), 96);
        d.camera.azimuth = 60.0;
        std::size_t before = 0;
        for (const double threshold : {600.0, 200.0, -100.0, -500.0}) {
            d.transferFunction.opacity = {{threshold - 1.0, 0.0}, {threshold + 100.0, 0.6}};
            const GpuRenderResult kept = gpu.renderWithGpuStats(d);
            GpuRayCaster fresh(volume_);
            const GpuRenderResult reference = fresh.renderWithGpuStats(d);
            QVERIFY2(kept.gpu.valueBytes >= before, "a wider transfer function needs more voxels");
            if (before > 0) {
                QVERIFY(kept.gpu.bricksUploaded > 0); // boxes grew: re-fitted
            }
            before = kept.gpu.valueBytes;
            const double p = comparedPsnr(kept.frame.image, reference.frame.image,
                                          "refit_" + std::to_string(int(threshold)), 60.0);
            QVERIFY2(
                p >= 60.0,
                qPrintable(
                    QString("threshold %1: %2 dB against a fresh caster").arg(threshold).arg(p)));
        }
    }

    // Under a budget that holds part of level 0, bricks of several levels are
    // drawn; where they meet there is no seam: the frame equals the same
    // levels resampled into one volume and drawn at level 0 (nearest, so
    // that both sample the same voxels).
    void mixedLevelsHaveNoSeams() {
        RenderDescription d = describe(volume_, loadPreset("ct-bone"), 128);
        d.transferFunction.shading.enabled = false;
        d.sampling.interpolation = Interpolation::Nearest;
        d.camera.azimuth = 40.0;
        d.camera.elevation = 10.0;
        d.camera.zoom = 1.5;
        GpuRayCaster full(volume_);
        const std::size_t whole = full.renderWithGpuStats(d).gpu.valueBytes;
        GpuOptions tight;
        tight.budgetBytes = whole / 3;
        GpuRayCaster gpu(volume_, tight);
        const GpuRenderResult mixed = gpu.renderWithGpuStats(d);
        std::set<int> levels;
        for (const std::int8_t l : mixed.gpu.levelOfBrick) {
            if (l >= 0) {
                levels.insert(l);
            }
        }
        QVERIFY2(levels.size() >= 2 && levels.count(0) == 1,
                 qPrintable(QString("levels drawn: %1").arg(levels.size())));
        QVERIFY(!mixed.gpu.lodReason.empty());
        const Volume resampled = resampledAtFrameLevels(volume_, mixed.gpu);
        GpuRayCaster referenceGpu(resampled);
        RenderDescription r = d;
        r.volume = &resampled;
        const GpuRenderResult reference = referenceGpu.renderWithGpuStats(r);
        QCOMPARE(reference.frame.stats.lod, 0);
        const double p =
            comparedPsnr(mixed.frame.image, reference.frame.image, "mixed_levels", 50.0);
        QVERIFY2(p >= 50.0, qPrintable(QString("mixed levels against resampled: %1 dB").arg(p)));
    }

    // Per-brick levels spend a tight budget where it shows: never worse than
    // one level for the whole volume, against the full render.
    void perBrickLevelsBeatOneLevel() {
        RenderDescription d = describe(volume_, loadPreset("ct-bone"), 128);
        GpuRayCaster full(volume_);
        const GpuRenderResult fine = full.renderWithGpuStats(d);
        GpuOptions perBrick, uniform;
        perBrick.budgetBytes = uniform.budgetBytes = fine.gpu.valueBytes / 2;
        uniform.lodPolicy = LodPolicy::Uniform;
        GpuRayCaster a(volume_, perBrick), b(volume_, uniform);
        const GpuRenderResult ra = a.renderWithGpuStats(d), rb = b.renderWithGpuStats(d);
        QVERIFY(ra.gpu.poolBytes <= perBrick.budgetBytes &&
                rb.gpu.poolBytes <= uniform.budgetBytes);
        const double pa = psnr(ra.frame.image, fine.frame.image);
        const double pb = psnr(rb.frame.image, fine.frame.image);
        QVERIFY2(pa >= pb - 0.25,
                 qPrintable(QString("per brick %1 dB, one level %2 dB").arg(pa).arg(pb)));
        QVERIFY(ra.gpu.bricksPerLevel.size() > 1 && ra.gpu.bricksPerLevel[0] > 0);
    }

    // A budget of a few bricks still renders, from coarse levels, and says why.
    void fewBricksStillRender() {
        RenderDescription d = describe(volume_, loadPreset("ct-bone"), 64);
        GpuOptions few;
        few.budgetBytes = 3 * 35 * 35 * 35 * 2; // three pages of 32 with their guard texels
        GpuRayCaster gpu(volume_, few);
        const GpuRenderResult r = gpu.renderWithGpuStats(d);
        QVERIFY(r.frame.stats.lod > 0);
        QVERIFY2(r.gpu.lodReason.find("budget") != std::string::npos, r.gpu.lodReason.c_str());
        QVERIFY(r.gpu.poolBytes <= few.budgetBytes);
        double sum = 0.0;
        for (const glm::vec4& px : r.frame.premultiplied) {
            sum += px.a;
        }
        QVERIFY2(sum > 10.0, "the coarse frame shows the volume");
    }

    // Under an upload cap the first frame shows coarse bricks and says how
    // many still stream in; later frames of the same view bring them in
    // until the frame is the uncapped one.
    void bricksStreamInUnderAnUploadCap() {
        RenderDescription d = describe(volume_, loadPreset("ct-bone"), 96);
        GpuRayCaster uncapped(volume_);
        const GpuRenderResult target = uncapped.renderWithGpuStats(d);
        GpuOptions capped;
        capped.uploadBytesPerFrame = target.gpu.bytesUploaded / 6;
        GpuRayCaster gpu(volume_, capped);
        GpuRenderResult r = gpu.renderWithGpuStats(d);
        QVERIFY2(r.gpu.pending > 0, "the first frame under a cap streams");
        QVERIFY(r.frame.stats.lod > 0);
        QVERIFY(r.gpu.lodReason.find("streaming") != std::string::npos);
        int frames = 1;
        while (r.gpu.pending > 0 && frames < 40) {
            const std::size_t before = r.gpu.pending;
            r = gpu.renderWithGpuStats(d);
            QVERIFY2(r.gpu.pending < before || r.gpu.pending == 0, "every frame brings some in");
            ++frames;
        }
        QCOMPARE(r.gpu.pending, std::size_t(0));
        QVERIFY(frames > 2);
        const double p = comparedPsnr(r.frame.image, target.frame.image, "streamed", 60.0);
        QVERIFY2(p >= 60.0, qPrintable(QString("after %1 frames: %2 dB").arg(frames).arg(p)));
    }

    // pageEntry, decoded as raycast_sampling.glsl's enterBrick does: negative
    // and large slots, every state and level, boxes up to 1023 voxels from
    // the brick's first; a field that does not fit is refused.
    void pageEntryHoldsPageAndBox() {
        const auto decode = [](glm::uvec4 e, glm::ivec3 first) {
            const auto signed16 = [](std::uint32_t v) { return int(std::int16_t(v & 0xffffu)); };
            const glm::ivec3 slot(signed16(e.x), signed16(e.x >> 16), signed16(e.y));
            const auto box = [&](std::uint32_t v) {
                return first + glm::ivec3(glm::uvec3(v, v >> 10, v >> 20) & 1023u);
            };
            return std::tuple(glm::ivec4(slot, int(e.y >> 16)), box(e.z), box(e.w));
        };
        const glm::ivec3 first(128, 64, 1984);
        for (const glm::ivec3 slot :
             {glm::ivec3(0), glm::ivec3(-61, 7, -32768), glm::ivec3(32767, -1, 2047)}) {
            for (int state = 0; state < 3; ++state) {
                for (int level = 0; level < 8; ++level) {
                    const glm::ivec4 page(slot, state | level << 2);
                    const SampleBox box{first + glm::ivec3(0, 3, 17),
                                        first + glm::ivec3(64, 1023, 40), true};
                    const auto [p, lo, hi] = decode(pageEntry(page, box, first), first);
                    QCOMPARE(p, page);
                    QCOMPARE(lo, box.lo);
                    QCOMPARE(hi, box.hi);
                }
            }
        }
        const SampleBox inside{first, first + 64, true};
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 pageEntry(glm::ivec4(32768, 0, 0, 1), inside, first));
        QVERIFY_THROWS_EXCEPTION(
            std::invalid_argument,
            pageEntry(glm::ivec4(0, 0, 0, 1), {first, first + 1024, true}, first));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, pageEntry(glm::ivec4(0, 0, 0, 1),
                                                                  {first - 1, first, true}, first));
        // So the GPU ray caster refuses bricks over kMaxPageBrickSize, naming the option.
        GpuRayCaster gpu(volume_);
        RenderDescription d = describe(volume_, loadPreset("ct-bone"), 32);
        d.sampling.brickSize = kMaxPageBrickSize + 1;
        try {
            gpu.render(d);
            QFAIL("a brick of 1024 voxels was taken");
        } catch (const std::invalid_argument& e) {
            QVERIFY2(std::string(e.what()).starts_with("brick: "), e.what());
        }
        d.sampling.brickSize = kMaxPageBrickSize;
        QVERIFY(!gpu.render(d).image.pixels.empty());
    }
};

QTEST_GUILESS_MAIN(TestGpuBricks)
#include "test_gpu_bricks.moc"
