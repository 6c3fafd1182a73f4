#pragma once
// Draws a teaching session's pointer and marks (render/TeachingMarks.h) over a
// server's frame: each mark's anchors projected with the frame's own projection,
// so that marks stay on the anatomy as the view turns; the pointer as a laser
// dot at its place in the view. The browser client draws them alike
// (resources/web/marks.js).

#include <QColor>
#include <QPainter>
#include <QRectF>

#include <array>

#include "render/TeachingMarks.h"

namespace lucent {

inline const QColor kMarkColour(0xff, 0x2b, 0xd6);
inline const QColor kPointerColour(0xff, 0x3b, 0x30);

// `image`: where the frame lies in the painter's coordinates; `projection`: the
// frame's (BackendFrame::projection).
void paintTeachingMarks(QPainter& painter, const QRectF& image, const TeachingMarks& marks,
                        const std::array<double, 12>& projection);

} // namespace lucent
