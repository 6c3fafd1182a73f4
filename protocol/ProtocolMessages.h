#pragma once
// Lucent remote render protocol (docs/protocol.md), everything a client or a
// server needs: the versions, the client's messages and their JSON, the server's
// messages and their JSON, the binary frame, and the conversion between a render
// description and view messages. Plain C++ (no Qt).

#include "protocol/ClientMessageJson.h"
#include "protocol/ClientMessages.h"
#include "protocol/FrameMessage.h"
#include "protocol/OptionValues.h"
#include "protocol/ProtocolError.h"
#include "protocol/ProtocolVersion.h"
#include "protocol/QrCode.h"
#include "protocol/Recording.h"
#include "protocol/ServerMessages.h"
#include "protocol/ViewMessages.h"
