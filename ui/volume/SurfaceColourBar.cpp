#include "ui/volume/SurfaceColourBar.h"

#include <QCoreApplication>
#include <QLinearGradient>
#include <QPainter>

#include "core/image/ColourMap.h"
#include "core/scene/SurfaceDisplay.h"

namespace lucent {

void paintSurfaceColourBar(QPainter& painter, const QRectF& area, const SurfaceDisplay& display,
                           double radiusMm) {
    if (!display.field) {
        return;
    }
    constexpr double kWidth = 14.0, kMargin = 10.0;
    const double height = std::min(220.0, area.height() * 0.5);
    const QRectF bar(area.right() - kMargin - kWidth, area.center().y() - height / 2.0, kWidth,
                     height);
    QLinearGradient ramp(bar.bottomLeft(), bar.topLeft());
    for (int n = 0; n <= 10; ++n) {
        const glm::dvec3 c = viridis(n / 10.0);
        ramp.setColorAt(n / 10.0, QColor::fromRgbF(float(c.r), float(c.g), float(c.b)));
    }
    painter.save();
    painter.fillRect(bar, ramp);
    painter.setPen(QColor(220, 220, 220));
    painter.drawRect(bar);
    const QFontMetricsF metrics(painter.font());
    const auto label = [&](double value, double y) {
        const QString text = QString::number(value, 'g', 3);
        painter.drawText(QPointF(bar.left() - 4.0 - metrics.horizontalAdvance(text), y), text);
    };
    label(display.fieldHi, bar.top() + metrics.ascent() / 2.0);
    label(display.fieldLo, bar.bottom() + metrics.ascent() / 2.0);
    const QString caption =
        QCoreApplication::translate("SurfaceColourBar", "SVR, R = %1 mm (1/mm)").arg(radiusMm);
    painter.drawText(QPointF(bar.right() - metrics.horizontalAdvance(caption),
                             bar.top() - metrics.descent() - 4.0),
                     caption);
    painter.restore();
}

} // namespace lucent
