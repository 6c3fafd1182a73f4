#pragma once

#include <QString>

#include <vector>

#include "core/quality/QualityFront.h"

namespace lucent::cli {

// Time per frame (log scale) against PSNR: every point, the front joined, and
// the 30-40 dB band the seed paper calls acceptable. Needs a QGuiApplication
// (fonts). Throws std::runtime_error when the file cannot be written.
void writeQualityPlot(const std::vector<QualityPoint>& points, const QString& path,
                      const QString& title);

} // namespace lucent::cli
