#pragma once
// The JSON of the slice messages (SliceMessages.h), for the protocol's readers
// and writers: ClientMessageJson (slices), FrameMessage (a slice frame's header)
// and ServerMessages (hello's presets). Private to protocol/.

#include <vector>

#include <nlohmann/json.hpp>

#include "protocol/SliceMessages.h"

namespace lucent::remote {

// Reads {"type":"slices",...}; throws bad-request naming the key.
SlicesRequest parseSlicesRequest(const nlohmann::json& m);
void writeSlicesRequest(nlohmann::json& m, const SlicesRequest& request);

// A slice frame's header fields, added to (and read from) a frame header;
// reading throws nlohmann's exceptions, which the frame reader turns into
// "malformed".
void writeSliceFrameInfo(nlohmann::json& header, const SliceFrameInfo& info);
SliceFrameInfo readSliceFrameInfo(const nlohmann::json& header);

nlohmann::json windowPresetsJson(const std::vector<WindowPresetInfo>& presets);
std::vector<WindowPresetInfo> readWindowPresets(const nlohmann::json& presets);

} // namespace lucent::remote
