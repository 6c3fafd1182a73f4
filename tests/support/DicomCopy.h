#pragma once
// What the test helpers that make new series from real DICOM files share (PriorStudy,
// PetFromCt): the files of a folder in order, new UIDs, elements set with a named error.

#include <filesystem>
#include <string>
#include <vector>

class DcmItem;
class DcmTagKey;

namespace lucent::test {

// The regular files directly in `folder`, sorted by name.
std::vector<std::filesystem::path> filesIn(const std::filesystem::path& folder);

// A new UID under DCMTK's `root` (SITE_STUDY_UID_ROOT, ...).
std::string newUid(const char* root);

// Sets the element, or removes it when `value` is empty. Throws std::runtime_error
// naming `file` and the element when DCMTK refuses the value.
void putElement(DcmItem& item, const DcmTagKey& tag, const std::string& value,
                const std::filesystem::path& file);

} // namespace lucent::test
