#include "QualityPlot.h"

#include "PlotCanvas.h"

#include <QPainterPath>

#include <algorithm>

namespace lucent::cli {

void writeQualityPlot(const std::vector<QualityPoint>& points, const QString& path,
                      const QString& title) {
    PlotAxes axes;
    axes.base = 10.0;
    axes.xLo = 1e300;
    axes.xHi = 0.0;
    for (const QualityPoint& q : points) {
        axes.xLo = std::min(axes.xLo, q.ms);
        axes.xHi = std::max(axes.xHi, q.ms);
    }
    axes.xUnit = " ms";
    axes.yMin = 10.0;
    axes.yMax = 70.0;
    axes.yStep = 10.0;
    axes.title = title;
    axes.caption = "time per frame (log)   |   green: 30-40 dB   |   fronts: red shaded (blue "
                   "points), orange unshaded (grey points)";
    axes.yLabel = "PSNR (dB) vs reference";
    axes.band = PlotAxes::Band{30.0, 40.0, QColor(210, 240, 210)};
    PlotCanvas canvas(axes);
    QPainter& p = canvas.painter();
    p.setPen(Qt::NoPen);
    for (const QualityPoint& q : points) {
        p.setBrush(q.setting.shading ? QColor(60, 90, 200, 150) : QColor(150, 150, 150, 150));
        p.drawEllipse(QPointF(canvas.x(q.ms), canvas.y(q.psnrDb)), 3.5, 3.5);
    }
    // One front per shading state: red shaded, orange unshaded.
    for (const bool shading : {true, false}) {
        std::vector<QualityPoint> front;
        std::copy_if(
            points.begin(), points.end(), std::back_inserter(front),
            [&](const QualityPoint& q) { return q.pareto && q.setting.shading == shading; });
        std::sort(front.begin(), front.end(),
                  [](const QualityPoint& a, const QualityPoint& b) { return a.ms < b.ms; });
        QPainterPath line;
        for (std::size_t n = 0; n < front.size(); ++n) {
            const QPointF at(canvas.x(front[n].ms), canvas.y(front[n].psnrDb));
            n == 0 ? line.moveTo(at) : line.lineTo(at);
        }
        p.setPen(QPen(shading ? QColor(200, 30, 30) : QColor(230, 140, 20), 2));
        p.setBrush(Qt::NoBrush);
        p.drawPath(line);
    }
    canvas.save(path);
}

} // namespace lucent::cli
