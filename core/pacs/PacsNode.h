#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace lucent {

// Every PACS failure: the message names the node and says what went wrong
// (refused, rejected, timed out, ...), in words a user can act on.
class PacsError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A DICOM node: its AE title, host and port.
struct PacsNode {
    std::string aeTitle;
    std::string host;
    int port = 104;

    std::string describe() const; // AET@HOST:PORT
    // Parses AET@HOST:PORT; throws PacsError naming the part that is wrong.
    static PacsNode parse(std::string_view spec);
};

struct PacsSettings {
    std::string callingAeTitle = "LUCENT"; // our AE title
    int connectTimeoutSeconds = 10;        // TCP connect and association negotiation
    int responseTimeoutSeconds = 30;       // each DIMSE response
};

// Throws PacsError when title is not a valid AE title (1-16 characters, no backslash or control).
void checkAeTitle(std::string_view title, std::string_view what);

} // namespace lucent
