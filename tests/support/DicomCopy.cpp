#include "tests/support/DicomCopy.h"

#include <algorithm>
#include <stdexcept>

#include <dcmtk/dcmdata/dcelem.h>
#include <dcmtk/dcmdata/dcitem.h>
#include <dcmtk/dcmdata/dcuid.h>

namespace lucent::test {

std::vector<std::filesystem::path> filesIn(const std::filesystem::path& folder) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        if (entry.is_regular_file()) {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::string newUid(const char* root) {
    char uid[100];
    return dcmGenerateUniqueIdentifier(uid, root);
}

void putElement(DcmItem& item, const DcmTagKey& tag, const std::string& value,
                const std::filesystem::path& file) {
    if (value.empty()) {
        delete item.remove(tag);
        return;
    }
    if (item.putAndInsertString(tag, value.c_str()).bad()) {
        throw std::runtime_error(file.string() + ": cannot set " + DcmTag(tag).getTagName());
    }
}

} // namespace lucent::test
