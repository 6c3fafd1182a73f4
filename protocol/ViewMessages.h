#pragma once
// Between a RenderDescription and the view messages that give a server's view
// that description: what a client sends (RemoteRenderBackend) and what a server
// applies (ViewStream), one conversion for both.

#include <optional>
#include <string>
#include <vector>

#include "core/scene/RenderDescription.h"
#include "protocol/ClientMessages.h"

namespace lucent::remote {

// The messages that make a view of `description`, in the order a client sends
// them: size (clamped to the wire's 16..4096), tf (the transfer function whole),
// mode (iso only for isosurfaces: it matters to nothing else), clip, camera and
// sampling (version 2). Applied in turn to a freshly opened view they give it
// the description's image size, transfer function, mode, clip box, camera and
// sampling (the options table's wire options).
std::vector<ClientMessage> viewMessages(const RenderDescription& description);

// Applies the change a view message makes to a description (size, tf, mode,
// clip, camera, sampling; quality, interaction and render change none of it).
// Returns why it cannot apply (a preset the server does not have), else nullopt.
std::optional<std::string> applyViewMessage(const ClientMessage& message,
                                            RenderDescription& description);

} // namespace lucent::remote
