#pragma once
// Where the server keeps recordings: DIR/recordings/<id>.jsonl, each written
// whole under DIR/tmp/ and renamed in (protocol/Recording.h has the format).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "protocol/ServerMessages.h"

namespace lucent::remote {

// The store lists at most this many recordings (the newest).
inline constexpr std::size_t kMaxListedRecordings = 256;

// 16 characters from 32 (80 random bits): an id no one guesses.
std::string newRecordingId();
std::filesystem::path recordingsDir(const std::filesystem::path& storeDir);
// The file of a recording (`id` as parseClientMessage checked it: no path in it).
std::filesystem::path recordingFile(const std::filesystem::path& storeDir, const std::string& id);
// The recordings of the store, newest first; files that are not recordings are skipped.
std::vector<RecordingSummary> listRecordings(const std::filesystem::path& storeDir);
// Writes `text` under DIR/tmp/ and renames it to the recording's file. Throws
// std::runtime_error naming the file when it cannot.
void storeRecording(const std::filesystem::path& storeDir, const std::string& id,
                    const std::string& text);

} // namespace lucent::remote
