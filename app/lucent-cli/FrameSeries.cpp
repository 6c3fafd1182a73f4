#include "FrameSeries.h"

#include <QElapsedTimer>

#include "CliCommand.h"
#include "app/bench/BenchScenes.h"

namespace lucent::cli {

FrameSeries renderFrames(Renderer& renderer, RenderDescription description, int repeat) {
    FrameSeries series;
    QElapsedTimer timer;
    for (int n = 0; n < repeat; ++n) {
        timer.start();
        RenderResult r = renderer.render(description);
        series.ms.push_back(double(timer.nsecsElapsed()) / 1e6);
        if (n == 0) {
            series.first = std::move(r);
            series.firstDetails = renderer.frameDetails();
        } else {
            renderer.recycle(std::move(r)); // as the workstation's view hands its frames back
        }
        description.camera.azimuth += 5.0;
    }
    series.lastDetails = renderer.frameDetails();
    return series;
}

QString seriesStats(double loadMs, const FrameSeries& series) {
    std::vector<double> frames = series.ms;
    QString text = "load_ms=" + QString::number(loadMs, 'f', 1);
    if (frames.size() > 1) {
        text += " first_ms=" + QString::number(frames.front(), 'f', 1);
        frames.erase(frames.begin());
    }
    const RenderStats& s = series.first.stats;
    return text + " render_ms=" + QString::number(bench::median(frames), 'f', 1) +
           " samples=" + QString::number(s.samples) +
           " bricks_total=" + QString::number(s.bricksTotal) +
           " bricks_used=" + QString::number(s.bricksUsed) + " lod=" + QString::number(s.lod);
}

} // namespace lucent::cli
