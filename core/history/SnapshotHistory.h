#pragma once
// Undo and redo by snapshots of a document's state: before each edit the state is kept
// with the edit's name; undo and redo swap it with the current one. The documents keep
// their state cheap to copy (measurements are small; segment masks are shared).

#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace lucent {

template <class State> class SnapshotHistory {
public:
    // At most `limit` undo steps are kept, the oldest dropped first.
    explicit SnapshotHistory(std::size_t limit = std::numeric_limits<std::size_t>::max())
        : limit_(limit == 0 ? 1 : limit) {}

    // Call before an edit: `current` is what an undo of the edit `what` returns to. Clears
    // the redo steps.
    void record(std::string what, const State& current) {
        undo_.push_back({std::move(what), current});
        if (undo_.size() > limit_) {
            undo_.erase(undo_.begin());
        }
        redo_.clear();
    }

    bool canUndo() const { return !undo_.empty(); }
    bool canRedo() const { return !redo_.empty(); }
    std::string undoText() const { return canUndo() ? undo_.back().what : std::string(); }
    std::string redoText() const { return canRedo() ? redo_.back().what : std::string(); }

    // Swaps `current` with the state before the last edit (after the last undone one for
    // redo); false, with `current` unchanged, when there is none.
    bool undo(State& current) { return step(undo_, redo_, current); }
    bool redo(State& current) { return step(redo_, undo_, current); }

    void clear() {
        undo_.clear();
        redo_.clear();
    }

private:
    struct Step {
        std::string what;
        State state;
    };
    static bool step(std::vector<Step>& from, std::vector<Step>& to, State& current) {
        if (from.empty()) {
            return false;
        }
        Step s = std::move(from.back());
        from.pop_back();
        std::swap(s.state, current);
        to.push_back(std::move(s));
        return true;
    }

    std::size_t limit_;
    std::vector<Step> undo_;
    std::vector<Step> redo_;
};

} // namespace lucent
