#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/history/SnapshotHistory.h"
#include "core/measure/Measurement.h"

namespace lucent {

// The measurements of one series, shared by every view of it, with an undo history
// of every edit (add, change, rename, remove, clear). Plain C++: the views draw it,
// the list panel lists it, the SR writer saves it whenever revision() changes.
class MeasurementDocument {
public:
    const std::vector<Measurement>& measurements() const { return measurements_; }
    const Measurement* find(std::uint64_t id) const;

    // Each edit below is one undo step; `what` describes it ("Add distance").
    std::uint64_t add(Measurement m);  // gives it a fresh id and returns it
    bool change(const Measurement& m); // replaces the one with m.id (points, text, label)
    bool rename(std::uint64_t id, const std::string& label);
    bool remove(std::uint64_t id);
    void clear();

    bool canUndo() const { return history_.canUndo(); }
    bool canRedo() const { return history_.canRedo(); }
    std::string undoText() const { return history_.undoText(); }
    std::string redoText() const { return history_.redoText(); }
    bool undo();
    bool redo();

    // Replaces everything with measurements read from storage, keeping their ids
    // (a fresh id for 0 or a repeated one); not an edit, and the history is cleared.
    void load(std::vector<Measurement> measurements);

    // Changes with every edit, undo, redo and load: what to save has changed.
    std::uint64_t revision() const { return revision_; }

private:
    void record(std::string what);
    std::vector<Measurement>::iterator locate(std::uint64_t id);

    std::vector<Measurement> measurements_;
    SnapshotHistory<std::vector<Measurement>> history_;
    std::uint64_t nextId_ = 1;
    std::uint64_t revision_ = 0;
};

} // namespace lucent
