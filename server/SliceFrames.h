#pragma once
// What the render thread makes for a view's MPR slices (protocol version 4,
// docs/protocol.md "Slices"): each asked view's plane through the crosshair,
// sampled and windowed by core/mpr exactly as the workstation's SliceView does,
// as a grey PNG frame whose header carries the plane.

#include <QByteArray>
#include <QMetaType>
#include <QString>

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/SeriesEntry.h"
#include "core/volume/Volume.h"
#include "protocol/SliceMessages.h"

namespace lucent::remote {

struct SliceJob {
    quint64 view = 0;
    std::shared_ptr<const SeriesEntry> series;
    std::vector<Orientation> views;
    glm::dvec3 crosshair{0.0};         // inside the volume
    std::optional<SliceWindow> window; // none: the volume's default window
    glm::ivec2 size{256, 256};
    std::uint64_t seq = 0;
    std::uint64_t generation = 0; // the stream's series: frames of an older one are dropped
};

struct RenderedSlices {
    quint64 view = 0;
    std::uint64_t seq = 0;
    std::uint64_t generation = 0;
    SliceWindow window; // the one used (the default, when the job had none)
    std::vector<std::pair<Orientation, QByteArray>> frames; // binary frame messages
    QString error;
};

// The frames of `job` from `volume` (its series' loaded volume). Throws on failure.
RenderedSlices renderSliceFrames(const Volume& volume, const SliceJob& job);

} // namespace lucent::remote

Q_DECLARE_METATYPE(lucent::remote::RenderedSlices)
