#include "core/exchange/SpatialRegistrationReader.h"

#include <cmath>
#include <stdexcept>

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcitem.h>
#include <dcmtk/dcmdata/dcuid.h>

namespace lucent {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
    throw std::runtime_error(file.string() + ": " + what);
}

std::string text(DcmItem& item, const DcmTagKey& tag) {
    OFString value;
    item.findAndGetOFString(tag, value);
    return value.c_str();
}

// FrameOfReferenceTransformationMatrix: 16 values, row-major, last row 0 0 0 1.
glm::dmat4 readMatrix(DcmItem& reg, const std::filesystem::path& file, int index) {
    const std::string where = "RegistrationSequence item " + std::to_string(index + 1);
    DcmItem* matrixRegistration = nullptr;
    DcmItem* matrix = nullptr;
    if (reg.findAndGetSequenceItem(DCM_MatrixRegistrationSequence, matrixRegistration, 0).bad() ||
        matrixRegistration->findAndGetSequenceItem(DCM_MatrixSequence, matrix, 0).bad()) {
        fail(file, where + ": no MatrixRegistrationSequence (0070,0309) > MatrixSequence");
    }
    glm::dmat4 m(1.0);
    for (unsigned long k = 0; k < 16; ++k) {
        double v = 0.0;
        if (matrix->findAndGetFloat64(DCM_FrameOfReferenceTransformationMatrix, v, k).bad() ||
            !std::isfinite(v)) {
            fail(file, where + ": FrameOfReferenceTransformationMatrix (3006,00C6) is not 16 "
                               "numbers");
        }
        m[static_cast<int>(k % 4)][static_cast<int>(k / 4)] = v; // glm: [column][row]
    }
    if (std::abs(m[0][3]) > 1e-9 || std::abs(m[1][3]) > 1e-9 || std::abs(m[2][3]) > 1e-9 ||
        std::abs(m[3][3] - 1.0) > 1e-9) {
        fail(file, where + ": FrameOfReferenceTransformationMatrix (3006,00C6) does not end "
                           "in 0 0 0 1");
    }
    if (std::abs(glm::determinant(m)) < 1e-12) {
        fail(file, where + ": FrameOfReferenceTransformationMatrix (3006,00C6) is singular");
    }
    return m;
}

} // namespace

SpatialRegistration readSpatialRegistration(const std::filesystem::path& file) {
    DcmFileFormat format;
    if (const OFCondition c = format.loadFile(file.c_str()); c.bad()) {
        fail(file, std::string("not readable as DICOM: ") + c.text());
    }
    DcmDataset& dataset = *format.getDataset();
    if (text(dataset, DCM_SOPClassUID) != UID_SpatialRegistrationStorage) {
        fail(file, "SOPClassUID (0008,0016) is not Spatial Registration Storage");
    }
    SpatialRegistration out;
    out.sopInstanceUid = text(dataset, DCM_SOPInstanceUID);
    out.frameOfReferenceUid = text(dataset, DCM_FrameOfReferenceUID);
    for (int i = 0;; ++i) {
        DcmItem* reg = nullptr;
        if (dataset.findAndGetSequenceItem(DCM_RegistrationSequence, reg, i).bad()) {
            break;
        }
        FrameRegistration frame;
        frame.frameOfReferenceUid = text(*reg, DCM_FrameOfReferenceUID);
        if (frame.frameOfReferenceUid.empty()) {
            fail(file, "RegistrationSequence item " + std::to_string(i + 1) +
                           ": no FrameOfReferenceUID (0020,0052)");
        }
        frame.toRegistered = readMatrix(*reg, file, i);
        out.frames.push_back(std::move(frame));
    }
    if (out.frames.empty()) {
        fail(file, "no RegistrationSequence (0070,0308) item");
    }
    return out;
}

std::optional<glm::dmat4> frameTransform(const SpatialRegistration& registration,
                                         const std::string& from, const std::string& to) {
    if (from.empty() || to.empty()) {
        return std::nullopt;
    }
    if (from == to) {
        return glm::dmat4(1.0);
    }
    const FrameRegistration* a = nullptr;
    const FrameRegistration* b = nullptr;
    for (const FrameRegistration& f : registration.frames) {
        if (f.frameOfReferenceUid == from && a == nullptr) {
            a = &f;
        }
        if (f.frameOfReferenceUid == to && b == nullptr) {
            b = &f;
        }
    }
    if (a == nullptr || b == nullptr) {
        return std::nullopt;
    }
    return glm::inverse(b->toRegistered) * a->toRegistered;
}

} // namespace lucent
