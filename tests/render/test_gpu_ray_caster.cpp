// The GPU ray caster against the CPU reference (double precision): every
// interpolation and mode, shaded, on the real Philips CT and on a volume made
// here; brick sizes against each other; empty-space leaping.
#include <QTest>

#include "core/scene/ViewFrame.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/render/GlTestSupport.h"

using namespace lucent;
using namespace lucent::test;

namespace {

RenderDescription reference(RenderDescription d) {
    d.sampling.precision = Precision::Double;
    return d;
}

// Blobs, a shell with a hole and a slanted plane, in int16 with an oblique
// direction and uneven spacing, so that geometry is exercised too.
// scale 1: 70 x 61 x 45 voxels.
Volume madeVolume(int scale = 1) {
    Volume v = makeVolume(
        {70 * scale, 61 * scale, 45 * scale},
        [scale](int i, int j, int k) {
            const glm::dvec3 p = glm::dvec3(i, j, k) / double(scale);
            const double r = glm::length(p - glm::dvec3(35, 30, 22));
            const double shell = std::abs(r - 17.0) < 2.5 && p.z < 34 ? 420.0 : 0.0;
            const double plane = std::abs(0.3 * p.x + 0.5 * p.y - p.z - 5.0) < 1.5 ? 250.0 : 0.0;
            return -200.0 + 6.0 * blobs(int(p.x / 2), int(p.y / 2), int(p.z)) + shell + plane;
        },
        VoxelType::Int16);
    VolumeGeometry g = v.geometry();
    g.spacing = {0.8, 0.8, 1.5};
    const double a = 0.3;
    g.direction =
        glm::dmat3({std::cos(a), std::sin(a), 0}, {-std::sin(a), std::cos(a), 0}, {0, 0, 1});
    g.origin = {-20, 10, 40};
    v.setGeometry(g);
    return v;
}

TransferFunction madeTf() {
    TransferFunction tf;
    tf.name = "made";
    tf.opacity = {{0.0, 0.0}, {150.0, 0.05}, {300.0, 0.5}, {600.0, 0.9}};
    tf.colour = {{0.0, {0.9, 0.4, 0.3}}, {300.0, {1.0, 0.9, 0.7}}, {600.0, {1, 1, 1}}};
    tf.shading.enabled = true;
    return tf;
}

struct Case {
    const char* name;
    Interpolation interp;
    RenderMode mode;
    bool preclassify, preintegrate;
};

const Case kCases[] = {
    {"dvr-nearest", Interpolation::Nearest, RenderMode::Dvr, false, false},
    {"dvr-linear", Interpolation::Linear, RenderMode::Dvr, false, false},
    {"dvr-cubic", Interpolation::Cubic, RenderMode::Dvr, false, false},
    {"dvr-linear-preclassified", Interpolation::Linear, RenderMode::Dvr, true, false},
    {"dvr-linear-preintegrated", Interpolation::Linear, RenderMode::Dvr, false, true},
    {"dvr-cubic-preintegrated", Interpolation::Cubic, RenderMode::Dvr, false, true},
    {"mip-linear", Interpolation::Linear, RenderMode::Mip, false, false},
    {"minip-linear", Interpolation::Linear, RenderMode::MinIp, false, false},
    {"avg-linear", Interpolation::Linear, RenderMode::Average, false, false},
    {"iso-linear", Interpolation::Linear, RenderMode::Isosurface, false, false},
    {"iso-cubic", Interpolation::Cubic, RenderMode::Isosurface, false, false},
    {"mip-cubic", Interpolation::Cubic, RenderMode::Mip, false, false},
};

} // namespace

class TestGpuRayCaster : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;

    void compareCases(const Volume& v, const TransferFunction& tf, const std::string& prefix,
                      int size, double azimuth, double elevation, double isoValue) {
        GpuRayCaster gpu(v);
        CpuRayCaster cpu(v);
        for (const Case& c : kCases) {
            RenderDescription d = describe(v, tf, size);
            d.camera.azimuth = azimuth;
            d.camera.elevation = elevation;
            d.mode = c.mode;
            d.isoValue = isoValue;
            d.sampling.interpolation = c.interp;
            d.sampling.classification = c.preclassify ? Classification::Pre : Classification::Post;
            d.sampling.preintegrate = c.preintegrate;
            const GpuRenderResult g = gpu.renderWithGpuStats(d);
            const RenderResult r = cpu.render(reference(d));
            const std::string name = prefix + "-" + c.name;
            const double p = comparedPsnr(g.frame.image, r.image, name, 40.0);
            QVERIFY2(p >= 40.0,
                     qPrintable(QString::fromStdString(name) +
                                QString(": psnr %1 dB against the CPU reference").arg(p)));
            QVERIFY2(g.frame.stats.samples > 0, c.name);
            qInfo("%s: %.2f dB", name.c_str(), p);
        }
    }

private slots:
    void initTestCase() {
        context_ = OffscreenContext::create();
        qInfo("GL: %s", context_->description().c_str());
    }

    void matchesReferenceOnMadeVolume() {
        const Volume v = madeVolume();
        compareCases(v, madeTf(), "made", 96, 30.0, 20.0, 200.0);
    }

    void matchesReferenceOnPhilipsCt() {
        if (!std::filesystem::exists(philipsCt())) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2020");
        }
        const Volume v = loadPath(philipsCt());
        compareCases(v, loadPreset("ct-bone"), "philips", 128, 20.0, 10.0, 300.0);
    }

    // No seams: every brick size, and one brick for the whole volume, give the
    // same image with the filter that reaches furthest (tricubic) and shading.
    void brickSizesAgree() {
        // (A failure prints the exception's message, e.g. a budget refusal.)
        const Volume v = madeVolume(3); // 210 x 183 x 135: two bricks of 128 per axis
        GpuRayCaster gpu(v);
        RenderDescription d = describe(v, madeTf(), 128);
        d.camera.azimuth = 40.0;
        d.camera.elevation = -15.0;
        d.sampling.interpolation = Interpolation::Cubic;
        d.sampling.brickSize = 256; // one brick: no borders at all
        const ImageRGBA8 whole = gpu.renderWithGpuStats(d).frame.image;
        for (const int size : {16, 32, 64, 128}) {
            d.sampling.brickSize = size;
            const GpuRenderResult r = gpu.renderWithGpuStats(d);
            const std::string name = "brick" + std::to_string(size);
            const double p = comparedPsnr(r.frame.image, whole, name, 50.0);
            QVERIFY2(p >= 50.0, qPrintable(QString("brick %1: psnr %2 dB").arg(size).arg(p)));
            QVERIFY(r.frame.stats.bricksTotal > 1);
            qInfo("brick %d: %.2f dB against one brick", size, p);
        }
    }

    // Leaping takes fewer samples and changes nothing, in every mode that leaps.
    void leapingCutsSamplesNotPixels() {
        const Volume v = loadOrMade();
        GpuRayCaster gpu(v);
        for (const RenderMode mode : {RenderMode::Dvr, RenderMode::Mip, RenderMode::Isosurface}) {
            RenderDescription d = describe(
                v, v.modality == "CT" && v.dims().x > 100 ? loadPreset("ct-bone") : madeTf(), 96);
            d.mode = mode;
            d.isoValue = 300.0;
            const GpuRenderResult leapt = gpu.renderWithGpuStats(d);
            d.sampling.emptySpaceLeaping = false;
            const GpuRenderResult full = gpu.renderWithGpuStats(d);
            QVERIFY2(leapt.frame.stats.samples < full.frame.stats.samples * 0.8,
                     qPrintable(QString("%1: %2 samples leaping, %3 without")
                                    .arg(renderModeName(mode))
                                    .arg(leapt.frame.stats.samples)
                                    .arg(full.frame.stats.samples)));
            QCOMPARE(maxDifference(leapt.frame.premultiplied, full.frame.premultiplied), 0.0f);
        }
    }

    // Shading from the cached gradients and from six fetches agree (nearest,
    // trilinear, pre-classified), and the cache is used when it fits (here
    // whatever memory it takes: the made volume shows almost everywhere).
    void gradientCacheMatchesComputedGradients() {
        const Volume v = madeVolume();
        GpuOptions off, always;
        off.gradientCache = false;
        always.gradientCacheShare = 0.0;
        GpuRayCaster cached(v, always), computed(v, off);
        for (const Interpolation interp : {Interpolation::Nearest, Interpolation::Linear}) {
            RenderDescription d = describe(v, madeTf(), 96);
            d.camera.azimuth = 25.0;
            d.sampling.interpolation = interp;
            const GpuRenderResult a = cached.renderWithGpuStats(d),
                                  b = computed.renderWithGpuStats(d);
            QVERIFY(a.gpu.gradientsCached);
            QVERIFY(!b.gpu.gradientsCached);
            const double p =
                comparedPsnr(a.frame.image, b.frame.image,
                             std::string("gradients-") + interpolationName(interp), 50.0);
            QVERIFY2(p >= 50.0, qPrintable(QString("cached vs computed: %1 dB").arg(p)));
        }
    }

    void clipBoxMatchesReference() {
        const Volume v = madeVolume();
        GpuRayCaster gpu(v);
        CpuRayCaster cpu(v);
        RenderDescription d = describe(v, madeTf(), 96);
        d.clip.lo = {10.5, 0, 5};
        d.clip.hi = {50, 40.25, 100};
        const double p = comparedPsnr(gpu.renderWithGpuStats(d).frame.image,
                                      cpu.render(reference(d)).image, "clip", 40.0);
        QVERIFY2(p >= 40.0, qPrintable(QString("psnr %1").arg(p)));
    }

    // The draw is scissored to the pixels whose rays can meet the clip box
    // (pixelsOfBox, in the image's rows, which run down where GL's run up): a
    // box in the top left corner of a turned view, off the image's centre
    // both ways, must come out whole.
    void raysAreCastWhereverTheClipBoxShows() {
        const Volume v = madeVolume();
        GpuRayCaster gpu(v);
        CpuRayCaster cpu(v);
        RenderDescription d = describe(v, madeTf(), 96);
        d.width = 120; // not square: the rows' flip and the columns both count
        d.camera.azimuth = 20.0;
        d.camera.elevation = 15.0;
        d.clip.lo = {0, 0, 24};
        d.clip.hi = {34, 60, 44};
        const GpuRenderResult gl = gpu.renderWithGpuStats(d);
        const RenderResult ref = cpu.render(reference(d));
        const double p = comparedPsnr(gl.frame.image, ref.image, "clip-corner", 40.0);
        QVERIFY2(p >= 40.0, qPrintable(QString("psnr %1").arg(p)));
        QVERIFY(gl.frame.stats.samples > 0);
    }

    // A drag and the still frames around it use two steps: each step's
    // pre-integration table is kept or made again, never mixed up.
    void preintegrationTablesOfTwoSteps() {
        const Volume v = loadOrMade();
        GpuRayCaster gpu(v);
        CpuRayCaster cpu(v);
        RenderDescription still = describe(v, loadPreset("ct-soft-tissue"), 96);
        still.sampling.preintegrate = true;
        still.sampling.step = 0.5;
        RenderDescription drag = still;
        drag.sampling.step = 1.0;
        RenderDescription other = still;
        other.sampling.step = 2.0;
        const ImageRGBA8 first = gpu.renderWithGpuStats(still).frame.image;
        const ImageRGBA8 dragged = gpu.renderWithGpuStats(drag).frame.image;
        for (int round = 0; round < 2; ++round) {
            QVERIFY(gpu.renderWithGpuStats(still).frame.image == first);
            QVERIFY(gpu.renderWithGpuStats(drag).frame.image == dragged);
        }
        (void)gpu.renderWithGpuStats(other); // a third step: the oldest table goes
        QVERIFY(gpu.renderWithGpuStats(drag).frame.image == dragged);
        QVERIFY(gpu.renderWithGpuStats(still).frame.image == first);
        for (const auto& [d, name] :
             {std::pair{still, "preint-step-0.5"}, {drag, "preint-step-1"}}) {
            const double p = comparedPsnr(gpu.renderWithGpuStats(d).frame.image,
                                          cpu.render(reference(d)).image, name, 40.0);
            QVERIFY2(p >= 40.0, qPrintable(QString("%1: psnr %2").arg(name).arg(p)));
        }
    }

private:
    static Volume loadOrMade() {
        if (std::filesystem::exists(philipsCt())) {
            return loadPath(philipsCt());
        }
        return madeVolume();
    }
};

QTEST_GUILESS_MAIN(TestGpuRayCaster)
#include "test_gpu_ray_caster.moc"
