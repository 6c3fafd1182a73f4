#pragma once
// Values of a dcmdata item, for the readers built on DCMTK (core/report's referenced series,
// core/segdicom's SEG reader). DCMTK's types are only named here.

#include <string>

class DcmItem;
class DcmTagKey;

namespace lucent::dicomitem {

// All of the element's values as stored ("\" between them); "" when absent.
std::string text(DcmItem& item, const DcmTagKey& tag);
// The element's first `count` values as numbers (DS or FD); false when it has fewer.
bool numbers(DcmItem& item, const DcmTagKey& tag, double* out, unsigned long count);

} // namespace lucent::dicomitem
