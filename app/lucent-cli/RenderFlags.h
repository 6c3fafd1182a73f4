#pragma once
// The render options of core/scene/RenderOptions.h on the command line: one
// flag per table row, with the table's help, default and checks.

#include <QCommandLineParser>

#include "core/scene/RenderDescription.h"

namespace lucent::cli {

// Adds a flag for every option of the table that has one.
void addRenderFlags(QCommandLineParser& parser);
// Applies every flag that is set to `description`. Throws
// std::invalid_argument naming the flag and what is wrong.
void applyRenderFlags(const QCommandLineParser& parser, RenderDescription& description);
// Whether any of these flags is set.
bool anyRenderFlagSet(const QCommandLineParser& parser);
// The description of `volume` the flags ask for: the table's options, the
// transfer function of --preset or --tf (which the parser must have) or the
// volume's default preset. Throws UsageError or std::invalid_argument.
RenderDescription describeFromFlags(const QCommandLineParser& parser, const Volume& volume);

} // namespace lucent::cli
