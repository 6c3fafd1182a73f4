#pragma once
// The Spatial Registration objects of the study store (Lucent's own, or another
// workstation's that came with a study): which Frames of Reference they relate, so two
// series of those frames link through them (ViewportLinks) without registering again.

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/exchange/SpatialRegistrationReader.h"

namespace lucent {

class StudyStore;

class StoredRegistrations {
public:
    // Reads every object of the store's REG series; one that cannot be used is left out and
    // its reason kept in problems().
    void load(const StudyStore& store);
    void clear();

    // Frame a's LPS mm -> frame b's, from the first object that relates both (the newest
    // series first); nullopt when none does or the frames are the same.
    std::optional<glm::dmat4> between(const std::string& frameA, const std::string& frameB) const;

    std::size_t size() const { return registrations_.size(); }
    const std::vector<std::string>& problems() const { return problems_; }

private:
    std::vector<SpatialRegistration> registrations_;
    std::vector<std::string> problems_;
};

} // namespace lucent
