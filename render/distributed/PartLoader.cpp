#include "render/distributed/PartLoader.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "core/dicom/SeriesLoader.h"
#include "core/formats/MetaImage.h"
#include "core/io/Catalog.h"
#include "core/raycast/BrickVisibility.h"
#include "core/raycast/PartHalo.h"
#include "render/distributed/RankAgreement.h"

namespace lucent {

namespace {

// Slices [k0, k1) of a DICOM entry that needs no resampling: an entry of just
// those images, so that the loader opens only their files.
SeriesEntry sliceRange(const SeriesEntry& e, int k0, int k1) {
    SeriesEntry sub = e;
    sub.slices.assign(e.slices.begin() + k0, e.slices.begin() + k1);
    sub.geometry =
        partGeometry(e.geometry, {0, 0, k0}, {e.geometry.dims.x, e.geometry.dims.y, k1 - k0});
    return sub;
}

// Value ranges of the bricks whose k index lies in [z0, z1), over each brick
// and one voxel around it (BrickGrid's overlap 1), from a slab holding the
// volume's slices [k0, ...). NaN voxels are ignored.
std::vector<glm::vec2> brickRanges(const Volume& slab, int k0, glm::ivec3 dims, int b,
                                   glm::ivec3 perAxis, int z0, int z1) {
    std::vector<glm::vec2> out(std::size_t(perAxis.x) * perAxis.y * std::size_t(z1 - z0));
    visitVoxels(slab, [&](auto v) {
#pragma omp parallel for schedule(dynamic)
        for (long n = 0; n < long(out.size()); ++n) {
            const int i = int(n % perAxis.x), j = int((n / perAxis.x) % perAxis.y),
                      k = z0 + int(n / (long(perAxis.x) * perAxis.y));
            const glm::ivec3 first = glm::max(glm::ivec3(i, j, k) * b - 1, glm::ivec3(0));
            const glm::ivec3 last = glm::min((glm::ivec3(i, j, k) + 1) * b + 1, dims);
            float lo = std::numeric_limits<float>::infinity(), hi = -lo;
            for (int z = first.z; z < last.z; ++z) {
                for (int y = first.y; y < last.y; ++y) {
                    for (int x = first.x; x < last.x; ++x) {
                        const float value = float(v[slab.linearIndex(x, y, z - k0)]);
                        if (value == value) {
                            lo = std::min(lo, value);
                            hi = std::max(hi, value);
                        }
                    }
                }
            }
            out[std::size_t(n)] = {lo, hi};
        }
    });
    return out;
}

std::vector<std::byte> asBytes(const std::vector<glm::vec2>& v) {
    std::vector<std::byte> out(v.size() * sizeof(glm::vec2));
    if (!v.empty()) {
        std::memcpy(out.data(), v.data(), out.size());
    }
    return out;
}

} // namespace

LoadedPart loadPart(const Communicator& comm, const SeriesEntry& entry,
                    const RenderDescription& description, int brickSize) {
    const auto start = std::chrono::steady_clock::now();
    const int ranks = comm.size(), rank = comm.rank();
    PartReadStats read;
    const std::string path =
        entry.format == SourceFormat::Dicom ? "series " + entry.id : entry.file;
    const SeriesEntry& e = entry;
    const glm::ivec3 dims = e.geometry.dims;
    const int halo = partHalo(description.sampling.interpolation, description.sampling.step);
    // DICOM slices, or the byte ranges of an uncompressed MetaImage's slices.
    const bool dicomSlabs =
        e.format == SourceFormat::Dicom && !e.resampled && int(e.slices.size()) == dims.z;
    bool rawSlabs = false;
    onEveryRank(comm, "reading the header of " + path, [&] {
        rawSlabs = e.format == SourceFormat::MetaImage && metaImageHasSliceRanges(e.file);
    });
    read.slabs = dicomSlabs || rawSlabs;
    // Slices [k0, k1) alone, as a volume whose index 0 is slice k0.
    const auto readSlices = [&](int k0, int k1) {
        Volume slab;
        if (rawSlabs) {
            read.files.push_back(e.file);
            slab = readMetaImageSlices(e.file, k0, k1);
        } else {
            const SeriesEntry slabEntry = sliceRange(e, k0, k1);
            for (const SliceRef& s : slabEntry.slices) {
                read.files.push_back(s.file);
            }
            slab = loadDicomSeries(slabEntry, {});
        }
        read.bytes += double(slab.byteCount());
        return slab;
    };

    // Pass 1: the bricks' value ranges, and the volume's.
    BrickTable table;
    table.dims = dims;
    table.brickSize = brickSize;
    table.perAxis = (dims + brickSize - 1) / brickSize;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    std::optional<Volume> whole; // read whole (no slab reading)
    std::vector<glm::vec2> mine;
    const int z0 = int(long(table.perAxis.z) * rank / ranks);
    const int z1 = int(long(table.perAxis.z) * (rank + 1) / ranks);
    onEveryRank(comm, "reading " + path + " for the split", [&] {
        if (!read.slabs) {
            whole = loadSeries(e);
            read.bytes += double(whole->byteCount());
            const BrickGrid grid(*whole, brickSize, 1);
            table = BrickTable::of(grid);
            std::tie(lo, hi) = whole->valueRange();
            if (e.format == SourceFormat::Dicom) {
                for (const SliceRef& s : e.slices) {
                    read.files.push_back(s.file);
                }
            } else {
                read.files.push_back(e.file);
            }
            return;
        }
        if (z0 == z1) {
            return; // more ranks than brick rows: this rank reads nothing in this pass
        }
        const int k0 = std::max(0, z0 * brickSize - 1);
        const int k1 = std::min(dims.z, z1 * brickSize + 1);
        const Volume slab = readSlices(k0, k1);
        mine = brickRanges(slab, k0, dims, brickSize, table.perAxis, z0, z1);
        std::tie(lo, hi) = slab.valueRange();
    });
    if (read.slabs) {
        const auto all = comm.allGather(asBytes(mine));
        table.range.clear();
        for (const auto& bytes : all) {
            const std::size_t n = bytes.size() / sizeof(glm::vec2);
            const std::size_t at = table.range.size();
            table.range.resize(at + n);
            if (n > 0) {
                std::memcpy(table.range.data() + at, bytes.data(), bytes.size());
            }
        }
        lo = comm.allMin(lo);
        hi = comm.allMax(hi);
    }

    // The split, the same on every rank (the same table, the same arithmetic).
    std::optional<VolumePartition> partition;
    onEveryRank(comm, "splitting the volume", [&] {
        // Slices lie along k: cuts across k let each rank read only its slab.
        partition.emplace(table, e.geometry.spacing, ranks, valueVisibility(description, lo, hi, 0),
                          read.slabs ? 2 : -1);
    });

    // Pass 2: this rank's box and halo.
    Volume voxels;
    const auto [first, last] = partVoxels(partition->box(rank), dims, halo);
    onEveryRank(comm, "reading its part of " + path, [&] {
        if (!read.slabs) {
            voxels = cutPart(*whole, first, last);
            whole.reset();
            read.firstSlice = first.z;
            read.lastSlice = last.z;
            return;
        }
        const Volume slab = readSlices(first.z, last.z);
        read.partBytes = double(slab.byteCount());
        read.firstSlice = first.z;
        read.lastSlice = last.z;
        voxels = cutPart(slab, {first.x, first.y, 0}, {last.x, last.y, last.z - first.z});
    });
    // A rank holds its box and halo, never more.
    const glm::ivec3 held = voxels.dims();
    const glm::ivec3 allowed =
        glm::min(partition->box(rank).hi - partition->box(rank).lo + 1 + 2 * halo, dims);
    if (glm::any(glm::greaterThan(held, allowed))) {
        throw std::logic_error("rank " + std::to_string(rank) +
                               " holds more voxels than its box "
                               "and halo");
    }
    std::sort(read.files.begin(), read.files.end());
    read.files.erase(std::unique(read.files.begin(), read.files.end()), read.files.end());
    read.readMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    LoadedPart part{
        std::move(voxels),     VolumePart{e.geometry, first, partition->box(rank), {lo, hi}},
        std::move(*partition), halo,
        std::move(read),       static_cast<const SeriesInfo&>(e)};
    part.voxels.setGeometry(partGeometry(e.geometry, first, last - first));
    static_cast<SeriesInfo&>(part.voxels) = part.info;
    return part;
}

} // namespace lucent
