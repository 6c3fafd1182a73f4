#pragma once
// The classic look of a PET projection (the rotating MIP): the maximum along each ray in
// inverted grey, white where nothing is taken up, black at the top of the window, on a
// white background. Plain C++ (lucent_core).

#include <glm/glm.hpp>

#include "core/tf/TransferFunction.h"
#include "core/volume/Volume.h"

namespace lucent {

inline constexpr const char* kPetMipTransferFunctionName = "pet-mip-inverted";

// Black everywhere, opacity rising linearly from 0 at lo to 1 at hi (and 1 above),
// unshaded. Shown as a projection on transferFunctionBackground's white, a value v is
// the grey 1 - opacity(v): lo and below white, hi and above black. Throws
// std::invalid_argument unless lo < hi.
TransferFunction petMipTransferFunction(double lo, double hi);
// The same over the window a volume opens with (defaultWindow: 0 to 6 SUV for PET in
// SUVbw, the 1st to 99th percentile of the stored units otherwise).
TransferFunction petMipTransferFunction(const Volume& volume);

// The background a render with this transfer function is shown on: white for
// petMipTransferFunction (by its name), black for every other.
glm::dvec3 transferFunctionBackground(const TransferFunction& tf);

} // namespace lucent
