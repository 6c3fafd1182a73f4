#pragma once
// A view's MPR slices (protocol version 4): the crosshair, window, size and
// views its controller asked for with `slices`, the renders they owe, and the
// last frame of each slice view. Like the 3D frame: at most one render in
// flight, messages that arrive meanwhile merged into the next, and only the
// newest frame of each slice view is ever sent (ClientConnection keeps one per
// view). A teaching session's members all get the same bytes; members whose
// connection speaks a version before 4 get none.

#include <QByteArray>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "protocol/SliceMessages.h"
#include "server/SliceFrames.h"

namespace lucent::remote {

class ClientConnection;
class RenderServer;
class ViewStream;

// The channel of a slice view's frames in ClientConnection::offerFrame (0 is the 3D view's).
int sliceChannel(Orientation view);

class SliceStream {
public:
    SliceStream(ViewStream& view, RenderServer& server);

    // The series changed or closed: the crosshair goes back to the volume's
    // centre, the window to the volume's default; no frames until the next show.
    void reset();
    // Applies a `slices` message and owes frames.
    void apply(const SlicesRequest& request);
    // Starts the next render when one is owed and the pacer has sent what it had.
    void pump();
    void deliver(const RenderedSlices& slices);
    // The last frame of each slice view (for members who join later).
    void offerLastFrames(ClientConnection& member) const;

private:
    ViewStream& view_;
    RenderServer& server_;
    bool active_ = false; // a `slices` message came since the series opened
    std::optional<glm::dvec3> crosshair_;
    std::optional<SliceWindow> window_;
    glm::ivec2 size_{256, 256};
    std::vector<Orientation> views_{Orientation::Axial, Orientation::Coronal,
                                    Orientation::Sagittal};
    std::uint64_t seq_ = 0;
    std::uint64_t generation_ = 0; // counts reset()s
    bool inFlight_ = false;
    bool wanted_ = false;
    std::array<QByteArray, 3> lastFrames_;
};

} // namespace lucent::remote
