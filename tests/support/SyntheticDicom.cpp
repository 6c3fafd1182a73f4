#include "SyntheticDicom.h"

#include <mutex>
#include <stdexcept>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcddirif.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcrleerg.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmjpeg/djencode.h>
#include <dcmtk/dcmjpeg/djrplol.h>
#include <dcmtk/dcmjpeg/djrploss.h>
#include <dcmtk/oflog/oflog.h>

namespace lucent::test {
namespace {

std::string ds(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

std::string vec(std::initializer_list<double> values) {
    std::string s;
    for (double v : values) {
        s += (s.empty() ? "" : "\\") + ds(v);
    }
    return s;
}

void registerCodecs() {
    static std::once_flag once;
    std::call_once(once, [] {
        OFLog::configure(OFLogger::ERROR_LOG_LEVEL); // DICOMDIR writing is chatty at INFO
        DJEncoderRegistration::registerCodecs();
        DcmRLEEncoderRegistration::registerCodecs();
    });
}

void check(const OFCondition& c, const std::string& what) {
    if (c.bad()) {
        throw std::runtime_error(what + ": " + c.text());
    }
}

void fillHeader(DcmDataset& d, const SyntheticSeries& s, int instanceNumber) {
    char uid[100];
    d.putAndInsertString(DCM_SOPClassUID,
                         s.modality == "MR" ? UID_MRImageStorage : UID_CTImageStorage);
    d.putAndInsertString(DCM_SOPInstanceUID,
                         dcmGenerateUniqueIdentifier(uid, SITE_INSTANCE_UID_ROOT));
    d.putAndInsertString(DCM_StudyInstanceUID, s.studyUid.c_str());
    d.putAndInsertString(DCM_SeriesInstanceUID, s.seriesUid.c_str());
    d.putAndInsertString(DCM_Modality, s.modality.c_str());
    d.putAndInsertString(DCM_SeriesDescription, s.description.c_str());
    d.putAndInsertString(DCM_PatientName, s.patientName.c_str());
    d.putAndInsertString(DCM_PatientID, s.patientId.c_str());
    d.putAndInsertString(DCM_StudyDate, s.studyDate.c_str());
    d.putAndInsertString(DCM_StudyTime, "120000");
    d.putAndInsertString(DCM_AccessionNumber, s.accessionNumber.c_str());
    d.putAndInsertString(DCM_ImageType, s.imageType.c_str());
    d.putAndInsertString(DCM_SeriesNumber, std::to_string(s.seriesNumber).c_str());
    d.putAndInsertString(DCM_InstanceNumber, std::to_string(instanceNumber).c_str());
    if (s.withGeometry) {
        d.putAndInsertString(
            DCM_ImageOrientationPatient,
            vec({s.rowDir.x, s.rowDir.y, s.rowDir.z, s.colDir.x, s.colDir.y, s.colDir.z}).c_str());
    }
    d.putAndInsertString(DCM_PixelSpacing, vec({s.pixelSpacing.y, s.pixelSpacing.x}).c_str());
    d.putAndInsertString(DCM_SliceThickness, "1");
    d.putAndInsertString(DCM_RescaleSlope, ds(s.slope).c_str());
    d.putAndInsertString(DCM_RescaleIntercept, ds(s.intercept).c_str());
    d.putAndInsertUint16(DCM_SamplesPerPixel, 1);
    d.putAndInsertString(DCM_PhotometricInterpretation, "MONOCHROME2");
    d.putAndInsertUint16(DCM_Rows, static_cast<Uint16>(s.rows));
    d.putAndInsertUint16(DCM_Columns, static_cast<Uint16>(s.columns));
    d.putAndInsertUint16(DCM_BitsAllocated, static_cast<Uint16>(s.bitsAllocated));
    d.putAndInsertUint16(DCM_BitsStored, static_cast<Uint16>(s.bitsStored));
    d.putAndInsertUint16(DCM_HighBit, static_cast<Uint16>(s.bitsStored - 1));
    d.putAndInsertUint16(DCM_PixelRepresentation, s.isSigned ? 1 : 0);
}

E_TransferSyntax syntaxOf(Encoding e) {
    switch (e) {
    case Encoding::ExplicitLittle:
        return EXS_LittleEndianExplicit;
    case Encoding::ImplicitLittle:
        return EXS_LittleEndianImplicit;
    case Encoding::ExplicitBig:
        return EXS_BigEndianExplicit;
    case Encoding::Deflated:
        return EXS_DeflatedLittleEndianExplicit;
    case Encoding::JpegBaseline:
        return EXS_JPEGProcess1;
    case Encoding::JpegLossless:
        return EXS_JPEGProcess14SV1;
    case Encoding::Rle:
        return EXS_RLELossless;
    }
    return EXS_LittleEndianExplicit;
}

} // namespace

std::string writeImage(const std::string& path, const SyntheticSeries& s, int image,
                       const glm::dvec3& position, int instanceNumber) {
    registerCodecs();
    DcmFileFormat file;
    DcmDataset& d = *file.getDataset();
    fillHeader(d, s, instanceNumber);
    if (s.withGeometry) {
        d.putAndInsertString(DCM_ImagePositionPatient,
                             vec({position.x, position.y, position.z}).c_str());
    }
    const std::size_t n = std::size_t(s.columns) * s.rows;
    const unsigned storedMask = (1u << s.bitsStored) - 1u;
    const unsigned dirty = s.dirtyHighBits ? ~storedMask : 0u;
    if (s.bitsAllocated == 8) {
        std::vector<Uint8> px(n);
        for (int j = 0; j < s.rows; ++j) {
            for (int i = 0; i < s.columns; ++i) {
                px[i + std::size_t(s.columns) * j] = static_cast<Uint8>(
                    (static_cast<unsigned>(s.stored(i, j, image)) & storedMask) | dirty);
            }
        }
        check(d.putAndInsertUint8Array(DCM_PixelData, px.data(), static_cast<unsigned long>(n)),
              "pixel data");
    } else {
        std::vector<Uint16> px(n);
        for (int j = 0; j < s.rows; ++j) {
            for (int i = 0; i < s.columns; ++i) {
                px[i + std::size_t(s.columns) * j] = static_cast<Uint16>(
                    (static_cast<unsigned>(s.stored(i, j, image)) & storedMask) | dirty);
            }
        }
        check(d.putAndInsertUint16Array(DCM_PixelData, px.data(), static_cast<unsigned long>(n)),
              "pixel data");
    }
    const E_TransferSyntax xfer = syntaxOf(s.encoding);
    if (s.encoding == Encoding::JpegBaseline) {
        const DJ_RPLossy params(95);
        check(d.chooseRepresentation(xfer, &params), "JPEG baseline encoding");
    } else if (s.encoding == Encoding::JpegLossless) {
        const DJ_RPLossless params;
        check(d.chooseRepresentation(xfer, &params), "JPEG lossless encoding");
    } else if (s.encoding == Encoding::Rle) {
        check(d.chooseRepresentation(xfer, nullptr), "RLE encoding");
    }
    check(file.saveFile(path.c_str(), xfer), "writing " + path);
    return path;
}

std::vector<std::string> writeSeries(const std::string& dir, const SyntheticSeries& s,
                                     const std::vector<glm::dvec3>& positions,
                                     const std::string& prefix) {
    std::vector<std::string> files;
    for (std::size_t n = 0; n < positions.size(); ++n) {
        files.push_back(writeImage(dir + "/" + prefix + std::to_string(n) + ".dcm", s,
                                   static_cast<int>(n), positions[n], static_cast<int>(n + 1)));
    }
    return files;
}

void writeWithoutPixelData(const std::string& path, const SyntheticSeries& s) {
    DcmFileFormat file;
    DcmDataset& d = *file.getDataset();
    fillHeader(d, s, 99);
    d.putAndInsertString(DCM_ImagePositionPatient, "0\\0\\0");
    check(file.saveFile(path.c_str(), EXS_LittleEndianExplicit), "writing " + path);
}

std::string writeDicomdir(const std::string& root, const std::vector<std::string>& relativeFiles) {
    registerCodecs();
    const std::string path = root + "/DICOMDIR";
    DicomDirInterface dir;
    dir.enableInventMode(OFTrue); // fill attributes the records need but tests do not set
    check(dir.createNewDicomDir(DicomDirInterface::AP_GeneralPurpose, path.c_str()), "DICOMDIR");
    for (const std::string& f : relativeFiles) {
        check(dir.addDicomFile(f.c_str(), root.c_str()), "DICOMDIR entry " + f);
    }
    check(dir.writeDicomDir(), "writing " + path);
    return path;
}

double expectedValue(const SyntheticSeries& s, int i, int j, int image) {
    const unsigned mask = (1u << s.bitsStored) - 1u;
    long v = static_cast<long>(static_cast<unsigned>(s.stored(i, j, image)) & mask);
    if (s.isSigned && (v & (1L << (s.bitsStored - 1)))) {
        v -= 1L << s.bitsStored;
    }
    return static_cast<double>(v) * s.slope + s.intercept;
}

} // namespace lucent::test
