#include "core/pet/PetProjection.h"

#include <stdexcept>
#include <string>

#include "core/mpr/PlaneSampler.h"

namespace lucent {

TransferFunction petMipTransferFunction(double lo, double hi) {
    if (!(lo < hi)) {
        throw std::invalid_argument("petMipTransferFunction: the window's low end " +
                                    std::to_string(lo) + " is not below its high end " +
                                    std::to_string(hi));
    }
    TransferFunction tf;
    tf.name = kPetMipTransferFunctionName;
    tf.opacity = {{lo, 0.0}, {hi, 1.0}};
    tf.colour = {{lo, glm::dvec3(0.0)}};
    tf.shading.enabled = false;
    return tf;
}

TransferFunction petMipTransferFunction(const Volume& volume) {
    const WindowLevel window = defaultWindow(volume);
    const double half = 0.5 * window.width;
    return petMipTransferFunction(window.center - half, window.center + half);
}

glm::dvec3 transferFunctionBackground(const TransferFunction& tf) {
    return tf.name == kPetMipTransferFunctionName ? glm::dvec3(1.0) : glm::dvec3(0.0);
}

} // namespace lucent
