#pragma once
// The ITK part of registerRigid, private to core/registration. Only RegistrationItk.cpp
// (helpers, the rigid stage, the checks) and RegistrationItkAffine.cpp (the affine stage)
// include ITK's headers, through RegistrationItkStage_p.h (its templates compile slowly).

#include <optional>

#include "core/registration/Registration.h"
#include "core/segmentation/SegmentMask.h"

namespace lucent::detail {

// registerRigid after the checks of Registration.cpp: `maskAbove` is the threshold of the
// intensity statistics (voxels above it); `mask` the fixed voxels the finest level samples
// (on the fixed volume's grid; the body without the air and the table);
// `initialisation` is Centres or FrameOfReference (Auto already resolved).
RegistrationResult registerItk(const Volume& fixed, const Volume& moving,
                               const RegistrationOptions& options, std::optional<double> maskAbove,
                               const SegmentMask& mask,
                               RegistrationOptions::Initialisation initialisation);

} // namespace lucent::detail
