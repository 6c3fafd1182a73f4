#pragma once
// The overlay of lucent-cli render and convert: --overlay PATH [--overlay-series UID]
// [--transform transform.json], the second series resampled onto the base's grid
// (core/fusion). Without --transform the identity, allowed only where both series
// share a Frame of Reference.

#include <QCommandLineParser>

#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "core/io/Catalog.h"
#include "core/volume/Volume.h"

namespace lucent::cli {

// Adds --overlay, --overlay-series and --transform.
void addOverlayFlags(QCommandLineParser& parser);

// Why render's command line cannot take its overlay flags ("" when it can): a flag of the
// overlay's style (--overlay-map, --overlay-window, --overlay-opacity) without --overlay, or
// --overlay with --distributed or a render server (ws://, wss://).
std::string renderOverlayUsage(const QCommandLineParser& parser);

// The base -> overlay transform: the matrix of --transform (core/fusion/TransformFile.h),
// else the identity when both series name the same Frame of Reference. Throws
// TransformFileError naming the file and field, or std::runtime_error naming both
// Frame of Reference UIDs when there is no --transform and they differ.
glm::dmat4 baseToOverlay(const QCommandLineParser& parser, const Volume& base,
                         const Volume& overlay);

// The overlay of --overlay resampled onto `base`'s grid (Float32, `fill` where the
// overlay has no value), or nullopt without --overlay. Throws UsageError for
// --overlay-series or --transform without --overlay, LoadError for a series that
// cannot be loaded, and what baseToOverlay throws.
std::optional<Volume> loadOverlay(const QCommandLineParser& parser, const Volume& base, float fill,
                                  const LoadControl& control = {});

} // namespace lucent::cli
