#pragma once
// A volume split into parts (VolumePartition, VolumePart), each part rendered
// by its own renderer, composited in one process as the distributed renderer
// composites across ranks: the in-process check of the part renderers.

#include <QTest>

#include <algorithm>
#include <vector>

#include "core/image/Image.h"
#include "core/image/ImageMetrics.h"
#include "core/raycast/BrickVisibility.h"
#include "core/raycast/PartHalo.h"
#include "core/raycast/PartProjection.h"
#include "core/scene/Renderer.h"
#include "core/scene/ViewFrame.h"
#include "core/volume/VolumePartition.h"

namespace lucent::test {

struct View {
    const char* name;
    double azimuth, elevation;
};
// Six axis views and two oblique ones.
inline constexpr View kViews[] = {{"front", 0, 0},     {"left", 90, 0},       {"back", 180, 0},
                                  {"right", 270, 0},   {"top", 0, 90},        {"bottom", 0, -90},
                                  {"oblique", 35, 25}, {"oblique2", 215, -40}};

struct Parts {
    VolumePartition partition;
    std::vector<Volume> volumes;
    std::vector<VolumePart> where;
};

inline Parts split(const Volume& whole, int count, const RenderDescription& d, int brickSize) {
    const BrickGrid grid(whole, brickSize, 1);
    const auto range = whole.valueRange();
    const auto visible = valueVisibility(d, range.first, range.second, 0);
    Parts p{
        VolumePartition(BrickTable::of(grid), whole.geometry().spacing, count, visible), {}, {}};
    const int halo = partHalo(d.sampling.interpolation, d.sampling.step);
    for (int n = 0; n < count; ++n) {
        const auto [first, last] = partVoxels(p.partition.box(n), whole.dims(), halo);
        p.volumes.push_back(cutPart(whole, first, last));
        p.where.push_back({whole.geometry(), first, p.partition.box(n), range});
    }
    return p;
}

struct Composite {
    ImageRGBA8 image;
    std::vector<glm::vec4> premultiplied;
    std::size_t samples = 0;
    std::vector<float> partAlpha; // summed alpha of each part's image
};

// Each part rendered by the Renderer `open(part volume, where)` gives, composited
// as the distributed renderer does: front to back (DVR, iso), by value (MIP,
// MinIP), by sums and counts (average).
template <class Open> Composite renderInParts(const Parts& parts, RenderDescription d, Open open) {
    const VolumeGeometry& g = parts.where[0].whole;
    const glm::dvec3 eye = g.toIndex(makeViewFrame(g, d.camera, d.width, d.height).eye);
    Composite c;
    c.premultiplied.assign(std::size_t(d.width) * d.height, glm::vec4(0.0f));
    c.partAlpha.assign(parts.volumes.size(), 0.0f);
    const bool projecting =
        d.mode == RenderMode::Mip || d.mode == RenderMode::MinIp || d.mode == RenderMode::Average;
    const auto [lo, hi] = parts.where[0].valueRange;
    std::vector<float> depth(c.premultiplied.size(), 1.0f);
    std::vector<glm::vec2> sums(c.premultiplied.size(), glm::vec2(0.0f));
    for (int n : parts.partition.frontToBack(eye)) {
        const auto caster = open(parts.volumes[std::size_t(n)], parts.where[std::size_t(n)]);
        d.volume = &parts.volumes[std::size_t(n)];
        const RenderResult r = caster->render(d);
        c.samples += r.stats.samples;
        for (std::size_t i = 0; i < c.premultiplied.size(); ++i) {
            c.partAlpha[std::size_t(n)] += r.premultiplied[i].a;
            if (!projecting) {
                c.premultiplied[i] += (1.0f - c.premultiplied[i].a) * r.premultiplied[i];
            } else if (d.mode == RenderMode::Average) {
                sums[i] += r.projection[i];
            } else if (const float z = projectionDepth(d.mode, r.projection[i], lo, hi);
                       z < depth[i]) {
                depth[i] = z;
                c.premultiplied[i] = r.premultiplied[i];
            }
        }
    }
    if (d.mode == RenderMode::Average) {
        for (std::size_t i = 0; i < sums.size(); ++i) {
            c.premultiplied[i] = averageColour(d.transferFunction, sums[i]);
        }
    }
    c.image = ImageRGBA8::filled(d.width, d.height, 255);
    for (std::size_t i = 0; i < c.premultiplied.size(); ++i) {
        const glm::dvec3 rgb =
            glm::dvec3(c.premultiplied[i]) + (1.0 - double(c.premultiplied[i].a)) * d.background;
        for (int ch = 0; ch < 3; ++ch) {
            c.image.pixels[i * 4 + std::size_t(ch)] =
                std::uint8_t(std::clamp(rgb[ch], 0.0, 1.0) * 255.0 + 0.5);
        }
    }
    return c;
}

// Moves the clip box so that part n has nothing left to draw: across an axis on
// which its box does not span the volume.
inline void clipAwayPart(RenderDescription& d, const Parts& p, int n, glm::ivec3 dims) {
    const PartBox box = p.partition.box(n);
    for (int a = 0; a < 3; ++a) {
        if (box.lo[a] > 0) {
            d.clip.hi[a] = double(box.lo[a]) - 0.5;
            return;
        }
        if (box.hi[a] < dims[a] - 1) {
            d.clip.lo[a] = double(box.hi[a]) + 0.5;
            return;
        }
    }
}

// From every view of kViews: the whole volume's render (`whole`) and the parts'
// composite, handed to check(view, whole frame, composite).
template <class Open, class Check>
void compareInViews(Renderer& whole, const Volume& volume, const Parts& p, RenderDescription d,
                    Open open, Check check) {
    for (const View& view : kViews) {
        d.camera.azimuth = view.azimuth;
        d.camera.elevation = view.elevation;
        d.volume = &volume;
        check(view, whole.render(d), renderInParts(p, d, open));
    }
}

// Every sample of the whole is taken once by the parts (none twice on a shared face).
template <class Open>
void expectEverySampleOnce(Renderer& whole, const Volume& volume, const Parts& p,
                           const RenderDescription& d, Open open) {
    compareInViews(whole, volume, p, d, open,
                   [&](const View& view, const RenderResult& reference, const Composite& c) {
                       QVERIFY2(c.samples == reference.stats.samples,
                                qPrintable(QString("%1 parts, %2: %3 samples in parts, %4 whole")
                                               .arg(p.volumes.size())
                                               .arg(view.name)
                                               .arg(c.samples)
                                               .arg(reference.stats.samples)));
                   });
}

// From every view: part n draws nothing, the others something, and their
// composite equals the whole volume's render >= 50 dB.
template <class Open>
void expectPartEmptied(Renderer& whole, const Volume& volume, const Parts& p,
                       const RenderDescription& d, int n, Open open) {
    compareInViews(whole, volume, p, d, open,
                   [&](const View& view, const RenderResult& reference, const Composite& c) {
                       QCOMPARE(c.partAlpha[std::size_t(n)], 0.0f);
                       float others = 0.0f;
                       for (std::size_t k = 0; k < c.partAlpha.size(); ++k) {
                           others += k == std::size_t(n) ? 0.0f : c.partAlpha[k];
                       }
                       QVERIFY(others > 0.0f);
                       QVERIFY2(psnr(reference.image, c.image) >= 50.0, view.name);
                   });
}

} // namespace lucent::test
