#pragma once

#include <QObject>

#include <glm/glm.hpp>

namespace lucent {

// What the linked MPR views share: the crosshair point (LPS mm), through which
// every view's plane passes, and the window/level of the grey mapping.
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

signals:
    void pointChanged();
    void windowChanged();

private:
    glm::dvec3 point_{0.0};
    double center_ = 40.0;
    double width_ = 400.0;
    double windowStep_ = 1.0;
};

} // namespace lucent
