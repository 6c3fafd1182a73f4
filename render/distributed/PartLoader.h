#pragma once
// Reading one rank's part of a volume (docs/distributed.md): each rank reads
// only the slices (DICOM files) its part covers, so that a volume larger than
// one node's memory can be rendered.
//
// Two passes, both collective. First every rank reads an even slab of brick
// rows and computes its bricks' value ranges; the ranges are shared, and the
// bricks are split among the ranks (VolumePartition: balanced by the bricks the
// description makes visible). Then each rank reads its part's box plus the
// halo the description's filters need: DICOM files of its slab, or the byte
// range of its slices in an uncompressed MetaImage. DICOM series that need
// resampling (tilted or uneven stacks), compressed MetaImages and other formats
// are read whole on every rank and cut (rank_slab_reading_min=0 in the figures).

#include <string>
#include <vector>

#include "core/io/SeriesEntry.h"
#include "core/scene/RenderDescription.h"
#include "core/volume/VolumePartition.h"
#include "render/distributed/Communicator.h"

namespace lucent {

struct PartReadStats {
    bool slabs = false;                // read slice by slice (false: whole, then cut)
    std::vector<std::string> files;    // the files this rank read, in either pass
    int firstSlice = 0, lastSlice = 0; // the second pass's slices [first, last)
    double bytes = 0.0;                // voxel bytes read, both passes
    double partBytes = 0.0;            // of them, the second pass's (the part and its halo)
    double readMs = 0.0;
};

struct LoadedPart {
    Volume voxels; // the part's box plus halo
    VolumePart where;
    VolumePartition partition; // the same on every rank
    int halo = 0;
    PartReadStats read;
    SeriesInfo info; // what the whole series is
};

// Loads this rank's part of the series `entry` (from scanPath), split for
// `description` (its transfer function, mode and sampling: visibility and
// halo) into comm.size() parts of bricks of `brickSize` voxels. Throws
// DistributedError on every rank when any rank fails, naming the rank and the
// cause (an unreadable file, too little memory, more ranks than bricks).
LoadedPart loadPart(const Communicator& comm, const SeriesEntry& entry,
                    const RenderDescription& description, int brickSize);

} // namespace lucent
