// The affine stage of registerRigid (Registration.h): ITK's AffineTransform started from
// the rigid stage's result. Apart from RegistrationItk.cpp so that the two stages'
// templates compile side by side.
#include <itkAffineTransform.h>

#include "core/registration/RegistrationItkStage_p.h"

namespace lucent::detail {

StageOutcome runAffineStage(const StageSetup& setup, const StagePart& part,
                            const RigidTransformType& rigid, glm::dmat4& fixedToMoving) {
    using AffineTransformType = itk::AffineTransform<double, 3>;
    // The same mapping as the rigid result, about the same centre: the physical-shift
    // scales then weigh the matrix entries by the extent of the fixed volume around it.
    auto affine = AffineTransformType::New();
    affine->SetCenter(rigid.GetCenter());
    affine->SetMatrix(rigid.GetMatrix());
    affine->SetTranslation(rigid.GetTranslation());
    const StageOutcome outcome = runStage(setup, part, *affine);
    fixedToMoving = toMatrix(*affine);
    return outcome;
}

} // namespace lucent::detail
