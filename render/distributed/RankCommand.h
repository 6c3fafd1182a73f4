#pragma once
// What rank 0 of a distributed render server asks of every rank
// (docs/distributed.md): render this frame of this series (each rank its
// part; IceT composites), or stop. Broadcast as JSON text.

#include <cstdint>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "core/io/SeriesEntry.h"
#include "core/scene/RenderDescription.h"

namespace lucent {

struct RankCommand {
    enum class Kind { Render, Stop };
    Kind kind = Kind::Stop;
    // Rank 0's number for the series entry: a series the store has grown
    // since (a new entry with the same id) gets a new number.
    std::uint64_t series = 0;
    std::string seriesId;   // its id in the catalog of seriesRoot
    std::string seriesRoot; // the folder (or file) that holds all its files: every rank scans it
    // What rank 0 sees, which every rank checks its scan against.
    std::uint64_t slices = 0;
    glm::ivec3 dims{0};
    RenderDescription description; // the frame (volume null)
};

// The render command for a frame of `entry` (rank 0's number `series`).
RankCommand renderCommand(std::uint64_t series, const SeriesEntry& entry,
                          const RenderDescription& description);

// The deepest folder that holds every file of a DICOM entry (recursively), or
// the file of another format.
std::string seriesRoot(const SeriesEntry& entry);

std::string encodeRankCommand(const RankCommand& command);
// Throws std::invalid_argument naming the field that is missing or malformed.
RankCommand decodeRankCommand(std::string_view text);

} // namespace lucent
