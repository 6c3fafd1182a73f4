#pragma once
// lucent-cli render --quality fast|balanced|best|<N>ms: the sampling chosen
// from the quick front of this volume on this backend, measured once and kept
// in the user's cache dir.

#include <QTextStream>

#include <string>

#include "core/quality/QualityChoice.h"

namespace lucent::cli {

// Sets desc's sampling to the choice for `request` and returns the --stats
// fields that say what was chosen (" quality=fast quality_step=2 ...").
// `render` renders with the backend named `backend`; the reference is the CPU.
// Progress and messages go to `err`.
std::string applyQuality(const QualityRequest& request, RenderDescription& desc,
                         const std::string& backend, const QualityRender& render, QTextStream& err);

} // namespace lucent::cli
