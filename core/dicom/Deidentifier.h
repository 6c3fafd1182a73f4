#pragma once
// De-identification of DICOM files after DICOM PS3.15 Annex E, the Basic
// Application Level Confidentiality Profile: the attributes of the profile
// (GDCM's table of them, and the further ones of Table E.1-1 that identify a
// person, a place or a time) are emptied (type 2 attributes such as Patient's
// Name and ID, Study Date), replaced (UIDs: by new ones, the same new UID for
// the same old one, so a series stays one series) or removed; private
// attributes, overlays and curves go; Patient Identity Removed (0012,0062)
// becomes YES. Pixel data and geometry are kept, so the copy loads as the same
// volume. Plain C++ (GDCM inside).

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace lucent {

class DeidentifyError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class Deidentifier {
public:
    // Writes a de-identified copy of `input` to `output`. Throws
    // DeidentifyError naming the file it cannot read or write, or one whose
    // Burned In Annotation (0028,0301) is YES (the profile cannot clean pixels).
    void deidentifyFile(const std::filesystem::path& input, const std::filesystem::path& output);

    // The replacement of a UID: new, and the same every time for the same UID.
    std::string replacementUid(const std::string& uid);

    // From now on Patient ID (0010,0020) becomes a dummy value, prefix and a
    // number, the same for the same original ID, instead of empty: the profile
    // allows either, and media whose DICOMDIR groups files by patient need one.
    void usePatientIdPseudonyms(std::string prefix) { patientIdPrefix_ = std::move(prefix); }
    // The dummy for an original Patient ID; empty unless pseudonyms are on.
    std::string replacementPatientId(const std::string& id);

private:
    std::map<std::string, std::string> uids_;
    std::map<std::string, std::string> patientIds_;
    std::string patientIdPrefix_;
};

// A new UID (GDCM's root and a random part).
std::string generateUid();

// De-identifies the files of one series into the folder `destination`, which
// must not exist yet: the copies (named 00001.dcm, 00002.dcm, ...) are written
// to a temporary sibling folder that is renamed to `destination` when all are
// written, so a reader never sees half a copy. One Deidentifier maps the UIDs
// of all files. Returns the new files in the order given. Throws DeidentifyError.
std::vector<std::filesystem::path> deidentifySeries(const std::vector<std::filesystem::path>& files,
                                                    const std::filesystem::path& destination);

} // namespace lucent
