#pragma once

#include <QImage>
#include <QString>

class QWidget;

namespace lucent {

// Screenshots of the workstation's views as images, and their export as PNG.

// What the view shows now, at its size in device pixels. A VolumeView is read
// through grabImage() (a QOpenGLWidget's pixels live in its framebuffer); any
// other widget through QWidget::grab().
QImage grabView(QWidget* view);

// The whole area (e.g. the view layout) with every visible VolumeView in it
// painted from its own grabImage().
QImage grabArea(QWidget* area);

// Writes image as PNG; on failure returns false and sets error (when given).
bool writePng(const QImage& image, const QString& file, QString* error = nullptr);

} // namespace lucent
