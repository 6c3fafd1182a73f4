#include "tests/support/RtDoseFromImage.h"

#include <memory>
#include <stdexcept>

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcmetinf.h>
#include <dcmtk/dcmdata/dcrleerg.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmdata/dcvrfd.h>
#include <dcmtk/dcmdata/dcvrus.h>

namespace lucent::test {
namespace {

void check(const OFCondition& c, const std::string& what) {
    if (c.bad()) {
        throw std::runtime_error(what + ": " + c.text());
    }
}

} // namespace

std::string writeRtDoseFromImage(const std::string& source, const std::string& path,
                                 RtDoseFlaw flaw) {
    DcmRLEEncoderRegistration::registerCodecs();
    DcmFileFormat file;
    check(file.loadFile(source.c_str()), "reading " + source);
    DcmDataset& d = *file.getDataset();
    check(d.putAndInsertString(DCM_SOPClassUID, UID_RTDoseStorage), "SOP class");
    check(file.getMetaInfo()->putAndInsertString(DCM_MediaStorageSOPClassUID, UID_RTDoseStorage),
          "media storage SOP class");
    check(d.putAndInsertString(DCM_DoseGridScaling, "0.001"), "dose grid scaling");
    check(d.putAndInsertString(DCM_GridFrameOffsetVector,
                               flaw == RtDoseFlaw::NoGridOffsets ? "" : "0"),
          "grid frame offsets");
    if (flaw == RtDoseFlaw::FrameCountAsUS) {
        auto e = std::make_unique<DcmUnsignedShort>(DcmTag(DCM_NumberOfFrames, EVR_US));
        check(e->putUint16(1), "frame count");
        check(d.insert(e.release(), true), "frame count");
    } else if (flaw == RtDoseFlaw::FrameCountAsFD) {
        auto e = std::make_unique<DcmFloatingPointDouble>(DcmTag(DCM_NumberOfFrames, EVR_FD));
        check(e->putFloat64(1.0), "frame count");
        check(d.insert(e.release(), true), "frame count");
    } else {
        check(d.putAndInsertString(DCM_NumberOfFrames, "1"), "frame count");
    }
    check(d.chooseRepresentation(EXS_RLELossless, nullptr), "RLE encoding");
    check(file.saveFile(path.c_str(), EXS_RLELossless), "writing " + path);
    return path;
}

} // namespace lucent::test
