#include "core/exchange/SpatialRegistrationWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <stdexcept>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcitem.h>
#include <dcmtk/dcmdata/dcuid.h>

namespace lucent {
namespace {

[[noreturn]] void fail(const std::filesystem::path& out, const std::string& cause) {
    throw std::runtime_error(out.string() + ": cannot write the spatial registration: " + cause);
}

void put(DcmItem& item, const DcmTagKey& tag, const std::string& value,
         const std::filesystem::path& out) {
    const OFCondition c = item.putAndInsertString(tag, value.c_str());
    if (c.bad()) {
        fail(out, std::string(DcmTag(tag).getTagName()) + ": " + c.text());
    }
}

DcmItem& newItem(DcmItem& parent, const DcmTagKey& sequence, const std::filesystem::path& out) {
    DcmItem* item = nullptr;
    const OFCondition c = parent.findOrCreateSequenceItem(sequence, item, -2 /* append */);
    if (c.bad() || item == nullptr) {
        fail(out, std::string(DcmTag(sequence).getTagName()) + ": " + c.text());
    }
    return *item;
}

// 16 DS values, row-major: row r, column c is glm's m[c][r].
std::string matrixValue(const glm::dmat4& m) {
    std::string s;
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) {
            char v[32];
            // DS holds at most 16 characters: %.10g of a value of a rigid matrix fits.
            double x = m[c][r];
            if (std::abs(x) < 1e-12) {
                x = 0.0;
            }
            std::snprintf(v, sizeof v, "%.10g", x);
            if (!s.empty()) {
                s += '\\';
            }
            s += v;
        }
    }
    return s;
}

void checkSeries(const RegisteredSeries& s, const char* which, const std::filesystem::path& out) {
    if (s.seriesUid.empty() || s.frameOfReferenceUid.empty()) {
        fail(out, std::string("the ") + which + " series has no series or Frame of Reference UID");
    }
    if (s.instances.empty()) {
        fail(out, std::string("the ") + which + " series has no instances");
    }
    for (const ReferencedInstance& i : s.instances) {
        if (i.sopClassUid.empty() || i.sopInstanceUid.empty()) {
            fail(out, std::string("an instance of the ") + which +
                          " series has no SOP class or instance UID");
        }
    }
}

// Frame of Reference Transformation Matrix Type (PS3.3 C.20.2.1.2): RIGID for a rotation
// and a translation, RIGID_SCALE when a uniform scale is added, AFFINE otherwise
// (lucent-cli register --affine).
const char* matrixType(const glm::dmat4& m) {
    const glm::dmat3 a(m);
    const glm::dmat3 gram = glm::transpose(a) * a; // s^2 I for a scaled rotation
    const double s2 = (gram[0][0] + gram[1][1] + gram[2][2]) / 3.0;
    double off = 0.0;
    for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) {
            off = std::max(off, std::abs(gram[c][r] - (r == c ? s2 : 0.0)));
        }
    }
    if (!(glm::determinant(a) > 0.0) || off > 1e-6 * std::max(s2, 1e-12)) {
        return "AFFINE";
    }
    return std::abs(s2 - 1.0) < 1e-6 ? "RIGID" : "RIGID_SCALE";
}

// One Registration Sequence item: a Frame of Reference, its images, its matrix.
void addRegistration(DcmItem& dataset, const RegisteredSeries& s, const glm::dmat4& toSro,
                     const std::string& comment, const std::filesystem::path& out) {
    DcmItem& reg = newItem(dataset, DCM_RegistrationSequence, out);
    put(reg, DCM_FrameOfReferenceUID, s.frameOfReferenceUid, out);
    for (const ReferencedInstance& i : s.instances) {
        DcmItem& image = newItem(reg, DCM_ReferencedImageSequence, out);
        put(image, DCM_ReferencedSOPClassUID, i.sopClassUid, out);
        put(image, DCM_ReferencedSOPInstanceUID, i.sopInstanceUid, out);
    }
    DcmItem& matrixRegistration = newItem(reg, DCM_MatrixRegistrationSequence, out);
    put(matrixRegistration, DCM_FrameOfReferenceTransformationComment, comment, out);
    // Registration Type Code Sequence (Type 2): empty.
    if (matrixRegistration.insertEmptyElement(DCM_RegistrationTypeCodeSequence).bad()) {
        fail(out, "RegistrationTypeCodeSequence");
    }
    DcmItem& matrix = newItem(matrixRegistration, DCM_MatrixSequence, out);
    put(matrix, DCM_FrameOfReferenceTransformationMatrix, matrixValue(toSro), out);
    put(matrix, DCM_FrameOfReferenceTransformationMatrixType, matrixType(toSro), out);
}

// Common Instance Reference Module: series of this study, then other studies.
void addReferences(DcmItem& dataset, const SpatialRegistrationInput& in,
                   const std::filesystem::path& out) {
    for (const RegisteredSeries* s : {&in.fixed, &in.moving}) {
        const bool sameStudy = s->studyUid.empty() || s->studyUid == in.studyUid;
        DcmItem* parent = &dataset;
        if (!sameStudy) {
            DcmItem& study =
                newItem(dataset, DCM_StudiesContainingOtherReferencedInstancesSequence, out);
            put(study, DCM_StudyInstanceUID, s->studyUid, out);
            parent = &study;
        }
        DcmItem& series = newItem(*parent, DCM_ReferencedSeriesSequence, out);
        put(series, DCM_SeriesInstanceUID, s->seriesUid, out);
        for (const ReferencedInstance& i : s->instances) {
            DcmItem& instance = newItem(series, DCM_ReferencedInstanceSequence, out);
            put(instance, DCM_ReferencedSOPClassUID, i.sopClassUid, out);
            put(instance, DCM_ReferencedSOPInstanceUID, i.sopInstanceUid, out);
        }
    }
}

std::string newUid() {
    char uid[100];
    dcmGenerateUniqueIdentifier(uid, SITE_INSTANCE_UID_ROOT);
    return uid;
}

} // namespace

SpatialRegistrationIds writeSpatialRegistration(const std::filesystem::path& out,
                                                const SpatialRegistrationInput& in) {
    if (in.studyUid.empty()) {
        fail(out, "no study UID");
    }
    checkSeries(in.fixed, "fixed", out);
    checkSeries(in.moving, "moving", out);
    if (in.fixed.frameOfReferenceUid == in.moving.frameOfReferenceUid) {
        fail(out, "the fixed and moving series share their Frame of Reference");
    }
    const double det = glm::determinant(in.fixedToMoving);
    if (!std::isfinite(det) || std::abs(det) < 1e-12) {
        fail(out, "the matrix cannot be inverted");
    }
    // PS3.3 C.20.2.1.1: the Frame of Reference Transformation Matrix of an item
    // transforms a point from the item's (registered) RCS into the RCS of the
    // Spatial Registration object, its Frame of Reference UID (0020,0052), which is
    // the fixed one here. So the moving item holds moving -> fixed, the inverse of
    // fixedToMoving; the fixed item holds the identity.
    const glm::dmat4 movingToFixed = glm::inverse(in.fixedToMoving);

    SpatialRegistrationIds ids{newUid(), newUid()};
    char date[16], time[16];
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    std::strftime(date, sizeof date, "%Y%m%d", &local);
    std::strftime(time, sizeof time, "%H%M%S", &local);

    DcmFileFormat file;
    DcmDataset& d = *file.getDataset();
    put(d, DCM_SpecificCharacterSet, "ISO_IR 192", out);
    // SOP Common
    put(d, DCM_SOPClassUID, UID_SpatialRegistrationStorage, out);
    put(d, DCM_SOPInstanceUID, ids.sopInstanceUid, out);
    put(d, DCM_InstanceCreationDate, date, out);
    put(d, DCM_InstanceCreationTime, time, out);
    // Patient
    put(d, DCM_PatientName, in.patientName, out);
    put(d, DCM_PatientID, in.patientId, out);
    put(d, DCM_PatientBirthDate, in.patientBirthDate, out);
    put(d, DCM_PatientSex, in.patientSex, out);
    // General Study
    put(d, DCM_StudyInstanceUID, in.studyUid, out);
    put(d, DCM_StudyDate, in.studyDate, out);
    put(d, DCM_StudyTime, in.studyTime, out);
    put(d, DCM_ReferringPhysicianName, "", out);
    put(d, DCM_StudyID, in.studyId, out);
    put(d, DCM_AccessionNumber, in.accessionNumber, out);
    // General Series, Spatial Registration Series
    put(d, DCM_Modality, "REG", out);
    put(d, DCM_SeriesInstanceUID, ids.seriesUid, out);
    put(d, DCM_SeriesNumber, std::to_string(in.seriesNumber), out);
    put(d, DCM_SeriesDescription, in.seriesDescription, out);
    // Laterality (Type 2C): a registration is of no one side; dciodvfy wants it present.
    put(d, DCM_Laterality, "", out);
    // Frame of Reference: the fixed (registered-to) one.
    put(d, DCM_FrameOfReferenceUID, in.fixed.frameOfReferenceUid, out);
    put(d, DCM_PositionReferenceIndicator, "", out);
    // General Equipment
    put(d, DCM_Manufacturer, "Lucent", out);
    put(d, DCM_SoftwareVersions, "Lucent", out);
    // Spatial Registration (with the Content Identification Macro)
    put(d, DCM_ContentDate, date, out);
    put(d, DCM_ContentTime, time, out);
    put(d, DCM_InstanceNumber, "1", out);
    put(d, DCM_ContentLabel, "LUCENT_REG", out);
    put(d, DCM_ContentDescription, in.contentDescription, out);
    put(d, DCM_ContentCreatorName, "", out);
    addRegistration(d, in.fixed, glm::dmat4(1.0), "Fixed (registered-to) series: identity", out);
    addRegistration(d, in.moving, movingToFixed,
                    "Moving series: maps its LPS mm into the fixed series' LPS mm", out);
    addReferences(d, in, out);

    const OFCondition c = file.saveFile(out.c_str(), EXS_LittleEndianExplicit);
    if (c.bad()) {
        fail(out, c.text());
    }
    return ids;
}

} // namespace lucent
