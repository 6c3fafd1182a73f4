#include "QualityOption.h"

#include <QDir>
#include <QStandardPaths>

#include "core/quality/MeasuredFront.h"

namespace lucent::cli {

std::string applyQuality(const QualityRequest& request, RenderDescription& desc,
                         const std::string& backend, const QualityRender& render,
                         QTextStream& err) {
    const QString cacheDir = QStandardPaths::writableLocation(QStandardPaths::CacheLocation);
    const std::filesystem::path cache = cacheDir.toStdString();
    const std::string key = frontKey(desc, backend);
    std::optional<MeasuredFront> front = cacheDir.isEmpty() ? std::nullopt : loadFront(cache, key);
    const bool cached = front.has_value();
    if (!front) {
        err << "lucent-cli render: measuring the quality front of this volume on "
            << backend.c_str() << " (once; kept in " << QDir::toNativeSeparators(cacheDir) << ")"
            << Qt::flush;
        CpuRayCaster reference(*desc.volume);
        front = measureQuickFront(
            desc, backend, render, [&](const RenderDescription& d) { return reference.render(d); },
            [&](std::size_t, std::size_t) { err << "." << Qt::flush; });
        err << "\n";
        try {
            if (!cacheDir.isEmpty()) {
                saveFront(cache, *front);
            }
        } catch (const std::exception& e) {
            err << "lucent-cli render: " << e.what()
                << " (the front is measured again next time)\n";
        }
    }
    const QualityChoice choice =
        chooseQuality(front->points, request.budgetMs, desc.transferFunction.shading.enabled,
                      front->timeModel(desc.width, desc.height));
    if (!choice.message.empty()) {
        err << "lucent-cli render: --quality " << request.name.c_str() << ": "
            << choice.message.c_str() << "\n";
    }
    desc = choice.setting.applyTo(desc);
    const QualitySetting& s = choice.setting;
    return " quality=" + request.name +
           " quality_budget_ms=" + QString::number(request.budgetMs, 'g', 6).toStdString() +
           " quality_step=" + QString::number(s.step, 'g', 6).toStdString() +
           " quality_interp=" + interpolationName(s.interpolation) +
           " quality_classification=" + s.classificationName() +
           " quality_brick=" + std::to_string(s.brickSize) +
           " quality_predicted_ms=" + QString::number(choice.predictedMs, 'f', 1).toStdString() +
           " quality_psnr_db=" + QString::number(choice.psnrDb, 'f', 2).toStdString() +
           " quality_within_budget=" + (choice.withinBudget ? "1" : "0") +
           " quality_front=" + (cached ? "cached" : "measured") + " quality_front_file=\"" +
           frontCachePath(cache, key).string() + "\"";
}

} // namespace lucent::cli
