#include "core/report/DicomItemValues.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcitem.h>

namespace lucent::dicomitem {

std::string text(DcmItem& item, const DcmTagKey& tag) {
    OFString v;
    return item.findAndGetOFStringArray(tag, v).good() ? std::string(v.c_str()) : std::string();
}

bool numbers(DcmItem& item, const DcmTagKey& tag, double* out, unsigned long count) {
    for (unsigned long i = 0; i < count; ++i) {
        Float64 v = 0.0;
        if (item.findAndGetFloat64(tag, v, i).bad()) {
            return false;
        }
        out[i] = v;
    }
    return true;
}

} // namespace lucent::dicomitem
