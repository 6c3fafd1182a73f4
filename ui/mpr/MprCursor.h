#pragma once

#include <array>

#include <QObject>

#include <glm/glm.hpp>

#include "core/mpr/PlaneSampler.h"
#include "core/volume/Volume.h"

namespace lucent {

// What the linked MPR views share: the crosshair point (LPS mm), through which
// every view's plane passes, the window/level of the grey mapping, and each
// orientation's rotation (oblique planes: the standard plane's axes turned by it).
class MprCursor : public QObject {
    Q_OBJECT

public:
    explicit MprCursor(QObject* parent = nullptr);

    const glm::dvec3& point() const { return point_; }
    void setPoint(const glm::dvec3& point);

    double windowCenter() const { return center_; }
    double windowWidth() const { return width_; }
    // The width is kept at least windowStep().
    void setWindow(double center, double width);
    // How much window or level one pixel of mouse drag changes (1 HU for CT).
    double windowStep() const { return windowStep_; }
    void setWindowStep(double step) { windowStep_ = step; }
    // Grey drawn inverted (high values dark): how PET is read, uptake black on white.
    bool invertedGrey() const { return invertedGrey_; }
    void setInvertedGrey(bool inverted);

    // The rotation applied to the standard plane of an orientation (identity: not oblique).
    const glm::dmat3& rotation(Orientation orientation) const;
    void setRotation(Orientation orientation, const glm::dmat3& rotation);
    void resetRotations();
    // The plane axes of an orientation after its rotation: u (screen right), v (screen
    // down) and the normal u x v, in LPS.
    glm::dvec3 planeU(Orientation orientation) const;
    glm::dvec3 planeV(Orientation orientation) const;
    glm::dvec3 planeNormal(Orientation orientation) const;

signals:
    void pointChanged();
    void windowChanged();
    void rotationChanged();

private:
    glm::dvec3 point_{0.0};
    double center_ = 40.0;
    double width_ = 400.0;
    double windowStep_ = 1.0;
    bool invertedGrey_ = false;
    std::array<glm::dmat3, 3> rotations_{glm::dmat3(1.0), glm::dmat3(1.0), glm::dmat3(1.0)};
};

// Where a cursor starts on a volume: the middle voxel (thin slices fall on voxel
// centres), the volume's default window, no rotation; grey inverted for PET (modality PT).
void centreOn(MprCursor& cursor, const Volume& volume);

} // namespace lucent
