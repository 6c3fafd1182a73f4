#pragma once
// The ITK part of registerRigid, private to core/registration. Only RegistrationItk.cpp
// (helpers, the rigid stage, the checks) and RegistrationItkAffine.cpp (the affine stage)
// include ITK's headers, through RegistrationItkStage_p.h (its templates compile slowly).

#include <optional>

#include "core/registration/Registration.h"

namespace lucent::detail {

// registerRigid after the checks of Registration.cpp: `maskAbove` is the fixed-image
// mask threshold (voxels above it are sampled), none to sample every voxel;
// `initialisation` is Centres or FrameOfReference (Auto already resolved).
RegistrationResult registerItk(const Volume& fixed, const Volume& moving,
                               const RegistrationOptions& options, std::optional<double> maskAbove,
                               RegistrationOptions::Initialisation initialisation);

} // namespace lucent::detail
