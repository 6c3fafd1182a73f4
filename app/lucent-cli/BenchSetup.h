#pragma once
// What the benches (bench quality, bench lod) take and give alike: the volume
// options, the preset, the plot's title and the CSV file.

#include <QCommandLineParser>
#include <QString>

#include <string>

#include "core/scene/RenderDescription.h"
#include "core/volume/Volume.h"

namespace lucent::cli {

// --series, --size (default 256x256), --preset and --csv.
void addVolumeBenchOptions(QCommandLineParser& parser);

// --preset, or the modality's default for `mode`.
std::string benchPreset(const QCommandLineParser& parser, const Volume& volume, RenderMode mode);

// "<series or path>, <preset>, <W>x<H>, <renderer>".
QString benchPlotTitle(const QString& path, const Volume& volume, const std::string& preset,
                       int width, int height, const QString& renderer);

// Writes `text` to --csv when it is set. Throws std::runtime_error naming the file.
void writeBenchCsv(const QCommandLineParser& parser, const QString& text);

} // namespace lucent::cli
