#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/hanging/HangingProtocol.h"

namespace lucent {

// A protocol file that cannot be read: "FILE: KEY: what is wrong".
class HangingProtocolError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Reads one protocol file (the format: resources/hanging/README.md). Throws
// HangingProtocolError naming the file and the key (bad JSON, an unknown key, a
// wrong type, a bad regex, a slot or window preset that does not exist, cells
// outside the grid or overlapping).
HangingProtocol readHangingProtocol(const std::filesystem::path& file);
// The same from text; `source` names it in errors.
HangingProtocol parseHangingProtocol(const std::string& text, const std::string& source);

// Writes every field but `file` (cells explicit), so that reading gives an equal
// protocol. Written whole or not at all. Throws HangingProtocolError naming the file.
void writeHangingProtocol(const std::filesystem::path& file, const HangingProtocol& protocol);

// Reads every *.json of the folders (sorted by file name; folders that do not exist
// are passed over). A name already read from an earlier folder is passed over
// (earlier folders win: put the user's first); the same name twice in one folder is
// an error. Files that cannot be read are left out, their errors appended to
// `errors` when given.
std::vector<HangingProtocol> loadHangingProtocols(const std::vector<std::filesystem::path>& folders,
                                                  std::vector<std::string>* errors = nullptr);

// Where the shipped protocols are, in order: $LUCENT_HANGING_DIR if set, the source
// tree's resources/hanging, <exe>/../share/lucent/hanging, the install prefix's
// share/lucent/hanging; only those that exist.
std::vector<std::filesystem::path> shippedHangingFolders();
// The user's protocols: <data home>/lucent/hanging, where data home is what Qt calls
// GenericDataLocation (the study store lives beside it, in <data home>/lucent/store);
// the workstation and lucent-cli share it.
std::filesystem::path userHangingFolder(const std::filesystem::path& dataHome);
// The user's folder, then the shipped ones: what loadHangingProtocols takes.
std::vector<std::filesystem::path> hangingFolders(const std::filesystem::path& userFolder);

// A file name for a protocol of this name: lower case, runs of other characters
// as '-', ".json" ("CT chest: prior" -> "ct-chest-prior.json").
std::string hangingProtocolFileName(const std::string& name);

} // namespace lucent
