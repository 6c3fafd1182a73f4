// A volume drawn in parts (VolumePart.h), each by its own CpuRayCaster over
// its box plus halo, composited front to back in the partition's order, equals
// the whole volume drawn at once: the parts share the global sample lattice,
// and a sample on a shared face is taken once.
#include <QFileInfo>
#include <QTest>

#include <algorithm>

#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/raycast/BrickVisibility.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/raycast/PartHalo.h"
#include "core/raycast/PartProjection.h"
#include "core/scene/ViewFrame.h"
#include "core/tf/TransferFunction.h"
#include "core/volume/VolumePartition.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/core/raycast/VolumeParts.h"

using namespace lucent;
using namespace lucent::test;

namespace {

std::unique_ptr<Renderer> openCpu(const Volume& part, const VolumePart& where) {
    return std::make_unique<CpuRayCaster>(part, where);
}

enum class Scene { Linear, Cubic, Shaded, Preintegrated, Iso, Nearest, Mip, MinIp, Average };

RenderDescription sceneOf(const Volume& v, Scene scene) {
    RenderDescription d = describe(v, rampTf(scene == Scene::Shaded || scene == Scene::Iso), 48);
    d.background = glm::dvec3(0.1, 0.2, 0.3);
    switch (scene) {
    case Scene::Cubic:
        d.sampling.interpolation = Interpolation::Cubic;
        d.transferFunction.shading.enabled = true;
        break;
    case Scene::Preintegrated:
        d.sampling.preintegrate = true;
        break;
    case Scene::Iso:
        d.mode = RenderMode::Isosurface;
        d.isoValue = 100.0;
        break;
    case Scene::Nearest:
        d.sampling.interpolation = Interpolation::Nearest;
        d.sampling.step = 0.7;
        break;
    case Scene::Mip:
        d.mode = RenderMode::Mip;
        break;
    case Scene::MinIp:
        d.mode = RenderMode::MinIp;
        d.transferFunction = flatTf(0.8);
        d.transferFunction.colour = {{0.0, {0.0, 0.0, 0.0}}, {200.0, {1.0, 1.0, 1.0}}};
        break;
    case Scene::Average:
        d.mode = RenderMode::Average;
        d.transferFunction.opacity = {{0.0, 0.0}, {60.0, 1.0}};
        break;
    case Scene::Linear:
    case Scene::Shaded:
        break;
    }
    return d;
}

const char* sceneName(Scene s) {
    switch (s) {
    case Scene::Linear:
        return "linear";
    case Scene::Cubic:
        return "cubic shaded";
    case Scene::Shaded:
        return "linear shaded";
    case Scene::Preintegrated:
        return "preintegrated";
    case Scene::Iso:
        return "iso";
    case Scene::Nearest:
        return "nearest";
    case Scene::Mip:
        return "mip";
    case Scene::MinIp:
        return "minip";
    case Scene::Average:
        return "average";
    }
    return "?";
}

} // namespace

class TestVolumeParts : public QObject {
    Q_OBJECT

    Volume volume_ = facesAndBlobs(VoxelType::Int16);

private slots:
    void partsEqualTheWhole_data() {
        QTest::addColumn<int>("scene");
        for (Scene s : {Scene::Linear, Scene::Cubic, Scene::Shaded, Scene::Preintegrated,
                        Scene::Iso, Scene::Nearest, Scene::Mip, Scene::MinIp, Scene::Average}) {
            QTest::newRow(sceneName(s)) << int(s);
        }
    }
    void partsEqualTheWhole() {
        QFETCH(int, scene);
        RenderDescription d = sceneOf(volume_, Scene(scene));
        CpuRayCaster whole(volume_);
        std::vector<RenderResult> references;
        for (const View& view : kViews) {
            d.camera.azimuth = view.azimuth;
            d.camera.elevation = view.elevation;
            references.push_back(whole.render(d));
        }
        for (int parts : {2, 3, 4}) {
            const Parts p = split(volume_, parts, d, 8);
            for (std::size_t v = 0; v < std::size(kViews); ++v) {
                d.camera.azimuth = kViews[v].azimuth;
                d.camera.elevation = kViews[v].elevation;
                const Composite c = renderInParts(p, d, openCpu);
                const double db = psnr(references[v].image, c.image);
                const float worst = maxDifference(references[v].premultiplied, c.premultiplied);
                QVERIFY2(db >= 50.0,
                         qPrintable(QString("%1 parts, %2: %3 dB, largest difference %4")
                                        .arg(parts)
                                        .arg(kViews[v].name)
                                        .arg(db)
                                        .arg(worst)));
            }
        }
    }

    // Without early termination and leaping every lattice sample is taken:
    // the parts take each of the whole's samples exactly once.
    void everySampleIsTakenOnce() {
        for (int parts : {2, 3, 4}) {
            RenderDescription d = sceneOf(volume_, Scene::Linear);
            d.sampling.earlyTermination = 1.0;
            d.sampling.emptySpaceLeaping = false;
            d.transferFunction = flatTf(0.01);
            // Half-voxel steps put the samples of an axis view's central ray
            // (an odd image size has one) exactly on the shared faces.
            d.sampling.step = 0.5;
            d.width = d.height = 49;
            CpuRayCaster whole(volume_);
            expectEverySampleOnce(whole, volume_, split(volume_, parts, d, 8), d, openCpu);
        }
    }

    // A clip box that leaves one part nothing to draw: that part's image is
    // empty and the composite still equals the whole.
    void aClipBoxEmptiesOnePart() {
        RenderDescription d = sceneOf(volume_, Scene::Shaded);
        const Parts p = split(volume_, 3, d, 8);
        clipAwayPart(d, p, 2, volume_.dims());
        CpuRayCaster whole(volume_);
        expectPartEmptied(whole, volume_, p, d, 2, openCpu);
    }

    // The real CT (Philips, 28 slices) in 2, 3 and 4 parts, bone preset.
    void realCtInParts() {
        const std::string dir = LUCENT_TEST_DATA_DIR "/dcm_qa_ct/Philips_S21570/S2010";
        if (!QFileInfo::exists(QString::fromStdString(dir))) {
            QSKIP("the Philips CT is not in ../shared/data");
        }
        const Volume ct = loadPath(dir, "", {});
        for (int parts : {2, 3, 4}) {
            // Cubic (the prefilter's halo) once: it is the slow one.
            for (bool cubic :
                 parts == 3 ? std::vector<bool>{false, true} : std::vector<bool>{false}) {
                RenderDescription d = describe(ct, loadPreset("ct-bone"), 64);
                d.sampling.interpolation = cubic ? Interpolation::Cubic : Interpolation::Linear;
                const Parts p = split(ct, parts, d, 32);
                CpuRayCaster whole(ct);
                for (const View& view : {kViews[0], kViews[4], kViews[6]}) {
                    d.camera.azimuth = view.azimuth;
                    d.camera.elevation = view.elevation;
                    d.volume = &ct;
                    const RenderResult reference = whole.render(d);
                    const Composite c = renderInParts(p, d, openCpu);
                    const double db = psnr(reference.image, c.image);
                    QVERIFY2(db >= 50.0, qPrintable(QString("%1 parts%2, %3: %4 dB")
                                                        .arg(parts)
                                                        .arg(cubic ? " cubic" : "")
                                                        .arg(view.name)
                                                        .arg(db)));
                }
            }
        }
    }
};

QTEST_APPLESS_MAIN(TestVolumeParts)
#include "test_volume_parts.moc"
