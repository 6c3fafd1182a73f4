#include "render/distributed/DistributedRenderer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/raycast/PartProjection.h"
#include "core/scene/ViewFrame.h"
#include "render/distributed/IceTCompositor.h"
#include "render/distributed/RankAgreement.h"

namespace lucent {

namespace {

// This process's resident memory in MiB (Linux: VmRSS), 0 where unknown.
double residentMib() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind("VmRSS:", 0) == 0) {
            std::istringstream in(line.substr(6));
            double kib = 0.0;
            in >> kib;
            return kib / 1024.0;
        }
    }
    return 0.0;
}

std::string fixed(double v, int digits = 1) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, v);
    return text;
}

} // namespace

DistributedRenderer::DistributedRenderer(const Communicator& comm, LoadedPart part,
                                         RendererKind kind)
    : comm_(comm), part_(std::move(part)) {
    onEveryRank(comm_, "opening its renderer", [&] {
        // GL ranks on a node with several GPUs each take their own, by local rank.
        device_ = RenderDevice::open(kind, comm_.localRank());
        RenderDevice::Opened opened = device_->openPartRenderer(part_.voxels, part_.where);
        caster_ = std::move(opened.renderer);
        fallback_ =
            !device_->fallbackReason().empty() ? device_->fallbackReason() : opened.fallbackReason;
        icet_ = std::make_unique<IceTCompositor>(comm_);
    });
    const double gl = comm_.allMin(caster_->backend() == "gl" ? 1.0 : 0.0);
    backend_ = gl > 0.0 ? "gl" : "cpu";
    partFigures_ = partFigures();
}

// What the ranks' parts hold and what reading them took: the same every frame,
// so gathered once.
FrameDetails DistributedRenderer::partFigures() const {
    const VolumeGeometry& whole = part_.where.whole;
    // What a rank may hold: its box grown by the halo on every side (clamped).
    const glm::dvec3 bound =
        glm::min(glm::dvec3(part_.where.owned.hi - part_.where.owned.lo + 1 + 2 * part_.halo),
                 glm::dvec3(whole.dims));
    double most[5] = {double(part_.voxels.geometry().voxelCount()), bound.x * bound.y * bound.z,
                      double(part_.read.files.size()), part_.read.bytes, part_.read.partBytes};
    comm_.allMax(most);
    const double slabs = comm_.allMin(part_.read.slabs ? 1.0 : 0.0);
    return {
        {"rank_voxels_max", fixed(most[0], 0)},
        {"rank_voxels_bound_max", fixed(most[1], 0)},
        {"volume_voxels", std::to_string(whole.voxelCount())},
        {"rank_files_read_max", fixed(most[2], 0)},
        {"rank_bytes_read_max", fixed(most[3], 0)},
        {"rank_part_bytes_read_max", fixed(most[4], 0)},
        {"rank_slab_reading_min", fixed(slabs, 0)},
    };
}

DistributedRenderer::~DistributedRenderer() = default;

std::string DistributedRenderer::device() const {
    return std::to_string(comm_.size()) + " ranks, " + caster_->device() + " each";
}

// DVR and iso (opaque hits): ordered blending. MIP and MinIP: IceT's depth
// test with the value as depth (the winning rank's colour is the colour of the
// winning value). Average: the ranks' sums and counts added up on rank 0.
std::vector<glm::vec4> DistributedRenderer::compositeParts(const RenderDescription& d,
                                                           const RenderResult& mine,
                                                           const std::vector<int>& order) {
    switch (d.mode) {
    case RenderMode::Dvr:
    case RenderMode::Isosurface: {
        const auto view = icet_->blend(d.width, d.height, mine.premultiplied, order);
        return {view.begin(), view.end()};
    }
    case RenderMode::Mip:
    case RenderMode::MinIp: {
        const auto [lo, hi] = part_.where.valueRange;
        std::vector<float> depth(mine.projection.size());
        for (std::size_t i = 0; i < depth.size(); ++i) {
            depth[i] = projectionDepth(d.mode, mine.projection[i], lo, hi);
        }
        const auto view = icet_->closest(d.width, d.height, mine.premultiplied, depth);
        return {view.begin(), view.end()};
    }
    case RenderMode::Average:
        break;
    }
    const auto start = std::chrono::steady_clock::now();
    std::vector<float> sums(mine.projection.size() * 2);
    for (std::size_t i = 0; i < mine.projection.size(); ++i) {
        sums[2 * i] = mine.projection[i].x;
        sums[2 * i + 1] = mine.projection[i].y;
    }
    comm_.sumTo(sums, 0);
    averageMs_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (comm_.rank() != 0) {
        return {};
    }
    std::vector<glm::vec4> out(mine.projection.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        out[i] = averageColour(d.transferFunction, {sums[2 * i], sums[2 * i + 1]});
    }
    return out;
}

RenderResult DistributedRenderer::render(const RenderDescription& description) {
    RenderDescription d = description;
    d.volume = &part_.voxels;
    d.validate(); // the same answer on every rank: the same description
    RenderResult mine;
    double renderMs = 0.0;
    onEveryRank(comm_, "rendering its part", [&] {
        const auto start = std::chrono::steady_clock::now();
        mine = caster_->render(d);
        renderMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
    });

    // Visibility order from this frame's eye: the k-d tree traversed from it.
    const VolumeGeometry& whole = part_.where.whole;
    const glm::dvec3 eye = whole.toIndex(makeViewFrame(whole, d.camera, d.width, d.height).eye);
    const std::vector<int> order = part_.partition.frontToBack(eye);
    // Ranks that finish early wait here, so that composite_ms is the compositing alone.
    const auto waitStart = std::chrono::steady_clock::now();
    comm_.barrier();
    const double waitMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - waitStart)
            .count();
    std::vector<glm::vec4> composite;
    onEveryRank(comm_, "compositing", [&] { composite = compositeParts(d, mine, order); });
    // Composited: the part's frame draws this rank's next frame of its size.
    const RenderStats partStats = mine.stats;
    caster_->recycle(std::move(mine));
    const bool recycled = frameDetail(caster_->frameDetails(), "frame_buffers") == "recycled";

    // Figures of every rank.
    // Samples and bricks summed over the ranks (their part grids, halos included).
    // Then: ranks whose part took no sample (a clip box left it nothing), and
    // ranks whose part was drawn into the buffers of their last frame (CPU).
    double sums[5] = {double(partStats.samples), double(partStats.bricksTotal),
                      double(partStats.bricksUsed), partStats.samples == 0 ? 1.0 : 0.0,
                      recycled ? 1.0 : 0.0};
    comm_.allSum(sums);
    // Per frame, one reduction each way: resident memory, bytes sent, render time.
    double most[3] = {residentMib(), icet_->last().bytesSent, renderMs};
    comm_.allMax(most);
    const double fastest = comm_.allMin(renderMs);
    details_ = {
        {"ranks", std::to_string(comm_.size())},
        {"ranks_empty", fixed(sums[3], 0)},
        {"ranks_frame_buffers_recycled", fixed(sums[4], 0)},
        {"composite_ms", fixed(d.mode == RenderMode::Average ? averageMs_ : icet_->last().totalMs)},
        {"icet_composite_ms", fixed(icet_->last().compositeMs)},
        {"rank0_wait_ms", fixed(waitMs)},
        {"render_ms_max", fixed(most[2])},
        {"render_ms_min", fixed(fastest)},
        {"rank_resident_mib_max", fixed(most[0])},
        {"icet_bytes_sent_max", fixed(most[1], 0)},
        {"icet_strategy", icet_->strategyName()},
        {"rank_backend_gl_min", backend_ == "gl" ? "1" : "0"},
    };
    details_.insert(details_.end(), partFigures_.begin(), partFigures_.end());

    RenderResult out;
    out.stats = partStats;
    out.stats.samples = std::size_t(sums[0]);
    out.stats.bricksTotal = std::size_t(sums[1]);
    out.stats.bricksUsed = std::size_t(sums[2]);
    if (comm_.rank() != 0) {
        return out;
    }
    out.premultiplied = std::move(composite);
    out.image = ImageRGBA8::filled(d.width, d.height, 255);
    const std::ptrdiff_t pixels = std::ptrdiff_t(out.premultiplied.size());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < pixels; ++i) {
        const glm::vec4 p = out.premultiplied[std::size_t(i)];
        const glm::dvec3 rgb = glm::dvec3(p) + (1.0 - double(p.a)) * d.background;
        for (int c = 0; c < 3; ++c) {
            out.image.pixels[std::size_t(i) * 4 + std::size_t(c)] =
                std::uint8_t(std::clamp(rgb[c], 0.0, 1.0) * 255.0 + 0.5);
        }
    }
    return out;
}

} // namespace lucent
