#pragma once
// The ITK part of registerRigid, private to core/registration: RegistrationItk.cpp is the
// only file that includes ITK's headers (its templates compile slowly).

#include <optional>

#include "core/registration/Registration.h"

namespace lucent::detail {

// registerRigid after the checks of Registration.cpp: `maskAbove` is the fixed-image
// mask threshold (voxels above it are sampled), none to sample every voxel.
RegistrationResult registerRigidItk(const Volume& fixed, const Volume& moving,
                                    const RegistrationOptions& options,
                                    std::optional<double> maskAbove);

} // namespace lucent::detail
