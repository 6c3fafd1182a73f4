#pragma once
// The segments of one series on its grid, with an undo history of every edit: each effect's
// result, a new, renamed, recoloured, recoded or removed segment, is one step. Plain C++:
// the views draw it, the Segments panel lists it, the SEG writer saves it whenever
// revision() changes. Masks are shared between steps until an edit replaces one, so a step
// costs the masks it changed.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/history/SnapshotHistory.h"
#include "core/segmentation/SegmentCodes.h"
#include "core/segmentation/SegmentMask.h"
#include "core/volume/Volume.h"

namespace lucent {

struct Segment {
    std::uint32_t id = 0; // given by Segmentation; unique within it
    std::string name;
    std::array<std::uint8_t, 3> colour{128, 128, 128};
    bool visible = true;
    bool locked = false; // effects leave it as it is
    CodedConcept category;
    CodedConcept type;
    // DICOM SEG's SegmentAlgorithmType: MANUAL, SEMIAUTOMATIC or AUTOMATIC, and the name of
    // the algorithm unless MANUAL ("Lucent threshold", ...).
    std::string algorithmType = "MANUAL";
    std::string algorithmName;
    std::shared_ptr<const SegmentMask> mask;
};

class Segmentation {
public:
    explicit Segmentation(const VolumeGeometry& grid, std::size_t historySteps = 20);

    const VolumeGeometry& geometry() const { return grid_; }
    const std::vector<Segment>& segments() const { return segments_; }
    const Segment* find(std::uint32_t id) const;

    // A new empty segment (of `kind` from the table: its codes and colour; else tissue).
    std::uint32_t add(const std::string& name, const SegmentKind* kind = nullptr);
    bool remove(std::uint32_t id);
    bool rename(std::uint32_t id, const std::string& name);
    bool setColour(std::uint32_t id, const std::array<std::uint8_t, 3>& colour);
    bool setKind(std::uint32_t id, const SegmentKind& kind);
    // Not edits (no undo step): what is shown and what effects may change.
    bool setVisible(std::uint32_t id, bool visible);
    bool setLocked(std::uint32_t id, bool locked);

    // An effect's result replaces the segment's voxels: one undo step named `what`. False
    // (nothing changes) for an unknown or locked segment; std::invalid_argument for a mask
    // of other dimensions. `algorithm` empty keeps the segment's algorithm fields; else the
    // type becomes SEMIAUTOMATIC (AUTOMATIC with automatic) and the name `algorithm`.
    bool setMask(std::uint32_t id, SegmentMask mask, const std::string& what,
                 const std::string& algorithm = {}, bool automatic = false);

    // Several segments' results as one undo step (grow from seeds): false, nothing changed,
    // when any segment is unknown or locked; std::invalid_argument for a mask of other
    // dimensions. `algorithm` as for setMask.
    bool setMasks(std::vector<std::pair<std::uint32_t, SegmentMask>> masks, const std::string& what,
                  const std::string& algorithm = {}, bool automatic = false);

    bool canUndo() const { return history_.canUndo(); }
    bool canRedo() const { return history_.canRedo(); }
    std::string undoText() const { return history_.undoText(); }
    std::string redoText() const { return history_.redoText(); }
    bool undo();
    bool redo();
    // Forgets every undo and redo step: what was loaded (a stored SEG) is where undo stops.
    void clearHistory() { history_.clear(); }

    // Changes with every edit, undo and redo: what to save has changed.
    std::uint64_t revision() const { return revision_; }

private:
    void record(std::string what);
    Segment* locate(std::uint32_t id);

    VolumeGeometry grid_;
    std::vector<Segment> segments_;
    SnapshotHistory<std::vector<Segment>> history_;
    std::uint32_t nextId_ = 1;
    std::uint64_t revision_ = 0;
};

} // namespace lucent
