#include "core/dicom/Deidentifier.h"
#include "core/dicom/DataSetStream_p.h"

#include <gdcmAnonymizer.h>
#include <gdcmDataSetHelper.h>
#include <gdcmDicts.h>
#include <gdcmGlobal.h>
#include <gdcmReader.h>
#include <gdcmSequenceOfItems.h>
#include <gdcmUIDGenerator.h>
#include <gdcmWriter.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <set>

namespace lucent {
namespace {

namespace fs = std::filesystem;

// What the profile does to an attribute: Z, X or U in Table E.1-1.
enum class Action { Empty, Remove, ReplaceUid };

struct ProfileRule {
    gdcm::Tag tag;
    Action action;
};

// Type 2 attributes of the common image IODs that the profile empties (Z)
// rather than removes, so the copy stays a valid instance.
const std::set<gdcm::Tag>& emptiedTags() {
    static const std::set<gdcm::Tag> tags{
        {0x0008, 0x0020}, // Study Date
        {0x0008, 0x0030}, // Study Time
        {0x0008, 0x0050}, // Accession Number
        {0x0008, 0x0090}, // Referring Physician's Name
        {0x0010, 0x0010}, // Patient's Name
        {0x0010, 0x0020}, // Patient ID
        {0x0010, 0x0030}, // Patient's Birth Date
        {0x0010, 0x0040}, // Patient's Sex
        {0x0020, 0x0010}, // Study ID
        {0x0008, 0x0023}, // Content Date
        {0x0008, 0x0033}, // Content Time
    };
    return tags;
}

// Attributes of PS3.15 Table E.1-1 (basic profile) beyond GDCM's table:
// dates and times, further names, addresses, IDs and references.
const gdcm::Tag kFurtherProfileTags[] = {
    {0x0008, 0x0012}, {0x0008, 0x0013}, {0x0008, 0x0015}, {0x0008, 0x0020}, {0x0008, 0x0021},
    {0x0008, 0x0022}, {0x0008, 0x0023}, {0x0008, 0x0024}, {0x0008, 0x0025}, {0x0008, 0x002a},
    {0x0008, 0x0030}, {0x0008, 0x0031}, {0x0008, 0x0032}, {0x0008, 0x0033}, {0x0008, 0x0034},
    {0x0008, 0x0035}, {0x0008, 0x0058}, {0x0008, 0x0082}, {0x0008, 0x0096}, {0x0008, 0x009c},
    {0x0008, 0x009d}, {0x0008, 0x0201}, {0x0008, 0x1049}, {0x0008, 0x1052}, {0x0008, 0x1062},
    {0x0008, 0x1072}, {0x0008, 0x1084}, {0x0008, 0x1110}, {0x0008, 0x1111}, {0x0008, 0x1120},
    {0x0008, 0x3010}, {0x0008, 0x4000}, {0x0010, 0x0021}, {0x0010, 0x0050}, {0x0010, 0x0101},
    {0x0010, 0x0102}, {0x0010, 0x1002}, {0x0010, 0x1005}, {0x0010, 0x1040}, {0x0010, 0x1060},
    {0x0010, 0x1080}, {0x0010, 0x1081}, {0x0010, 0x2000}, {0x0010, 0x2110}, {0x0010, 0x2150},
    {0x0010, 0x2152}, {0x0010, 0x2154}, {0x0010, 0x21a0}, {0x0010, 0x21c0}, {0x0010, 0x21d0},
    {0x0010, 0x21f0}, {0x0010, 0x2203}, {0x0010, 0x2297}, {0x0010, 0x2299}, {0x0018, 0x1002},
    {0x0018, 0x1004}, {0x0018, 0x1005}, {0x0018, 0x1007}, {0x0018, 0x1008}, {0x0018, 0x1400},
    {0x0018, 0x4000}, {0x0018, 0x700a}, {0x0018, 0x9424}, {0x0020, 0x9161}, {0x0020, 0x9164},
    {0x0032, 0x1032}, {0x0032, 0x1033}, {0x0032, 0x1060}, {0x0032, 0x1070}, {0x0032, 0x4000},
    {0x0038, 0x0010}, {0x0038, 0x0300}, {0x0038, 0x0400}, {0x0038, 0x0500}, {0x0040, 0x0006},
    {0x0040, 0x0007}, {0x0040, 0x0241}, {0x0040, 0x0242}, {0x0040, 0x0243}, {0x0040, 0x0244},
    {0x0040, 0x0245}, {0x0040, 0x0250}, {0x0040, 0x0251}, {0x0040, 0x0253}, {0x0040, 0x0254},
    {0x0040, 0x0280}, {0x0040, 0x1001}, {0x0040, 0x1400}, {0x0040, 0x2400}, {0x0040, 0xa075},
    {0x0040, 0xa123}, {0x0400, 0x0561}, {0x0004, 0x1511},
};

bool isUidTag(const gdcm::Tag& tag) {
    static const gdcm::Dicts& dicts = gdcm::Global::GetInstance().GetDicts();
    return dicts.GetDictEntry(tag).GetVR() == gdcm::VR::UI;
}

const std::vector<ProfileRule>& profile() {
    static const std::vector<ProfileRule> rules = [] {
        std::set<gdcm::Tag> tags;
        for (const gdcm::Tag& t :
             gdcm::Anonymizer::GetBasicApplicationLevelConfidentialityProfileAttributes()) {
            tags.insert(t);
        }
        tags.insert(std::begin(kFurtherProfileTags), std::end(kFurtherProfileTags));
        std::vector<ProfileRule> out;
        for (const gdcm::Tag& t : tags) {
            const Action action = isUidTag(t)              ? Action::ReplaceUid
                                  : emptiedTags().count(t) ? Action::Empty
                                                           : Action::Remove;
            out.push_back({t, action});
        }
        return out;
    }();
    return rules;
}

// Curves (50xx) and overlays (60xx), even groups: they may hold burnt-in text.
bool isCurveOrOverlay(const gdcm::Tag& tag) {
    const uint16_t g = tag.GetGroup();
    return g % 2 == 0 && ((g >= 0x5000 && g <= 0x501e) || (g >= 0x6000 && g <= 0x601e));
}

std::string valueOf(const gdcm::DataElement& de) {
    const gdcm::ByteValue* bv = de.GetByteValue();
    if (!bv) {
        return {};
    }
    std::string s(bv->GetPointer(), bv->GetLength());
    while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) {
        s.pop_back();
    }
    return s;
}

void setUid(gdcm::DataElement& de, std::string uid) {
    if (uid.size() % 2 != 0) {
        uid.push_back('\0'); // UIDs are padded with NUL to an even length
    }
    de.SetByteValue(uid.data(), gdcm::VL(uint32_t(uid.size())));
}

} // namespace

std::string generateUid() {
    gdcm::UIDGenerator generator;
    return generator.Generate();
}

std::string Deidentifier::replacementUid(const std::string& uid) {
    auto [it, inserted] = uids_.try_emplace(uid);
    if (inserted) {
        it->second = generateUid();
    }
    return it->second;
}

std::string Deidentifier::replacementPatientId(const std::string& id) {
    if (patientIdPrefix_.empty()) {
        return {};
    }
    auto [it, inserted] = patientIds_.try_emplace(id);
    if (inserted) {
        char number[16];
        std::snprintf(number, sizeof number, "%04zu", patientIds_.size());
        it->second = patientIdPrefix_ + number;
    }
    return it->second;
}

namespace {

// Applies the profile to one data set and, recursively, to its sequences' items.
void protect(const gdcm::File& file, gdcm::DataSet& ds, Deidentifier& deidentifier) {
    for (const ProfileRule& rule : profile()) {
        if (!ds.FindDataElement(rule.tag)) {
            continue;
        }
        gdcm::DataElement de = ds.GetDataElement(rule.tag);
        switch (rule.action) {
        case Action::Remove:
            ds.Remove(rule.tag);
            break;
        case Action::Empty: {
            std::string dummy;
            if (rule.tag == gdcm::Tag(0x0010, 0x0020)) {
                dummy = deidentifier.replacementPatientId(valueOf(de));
            }
            if (dummy.empty()) {
                de.Empty();
            } else {
                dummy.resize(dummy.size() + dummy.size() % 2, ' ');
                de.SetByteValue(dummy.data(), gdcm::VL(uint32_t(dummy.size())));
            }
            ds.Replace(de);
            break;
        }
        case Action::ReplaceUid: {
            const std::string old = valueOf(de);
            setUid(de, old.empty() ? generateUid() : deidentifier.replacementUid(old));
            ds.Replace(de);
            break;
        }
        }
    }
    std::vector<gdcm::Tag> dropped;
    std::vector<gdcm::DataElement> sequences;
    for (const gdcm::DataElement& de : ds.GetDES()) {
        const gdcm::Tag& tag = de.GetTag();
        if (tag.IsPrivate() || isCurveOrOverlay(tag)) {
            dropped.push_back(tag);
        } else if (gdcm::DataSetHelper::ComputeVR(file, ds, tag) == gdcm::VR::SQ) {
            sequences.push_back(de);
        }
    }
    for (const gdcm::Tag& tag : dropped) {
        ds.Remove(tag);
    }
    for (gdcm::DataElement& de : sequences) {
        const gdcm::SmartPointer<gdcm::SequenceOfItems> items = de.GetValueAsSQ();
        if (!items) {
            continue;
        }
        for (gdcm::SequenceOfItems::SizeType n = 1; n <= items->GetNumberOfItems(); ++n) {
            protect(file, items->GetItem(n).GetNestedDataSet(), deidentifier);
        }
        de.SetValue(*items);
        de.SetVLToUndefined();
        ds.Replace(de);
    }
}

void replaceText(gdcm::DataSet& ds, const gdcm::Tag& tag, gdcm::VR vr, std::string value) {
    if (value.size() % 2 != 0) {
        value.push_back(' ');
    }
    gdcm::DataElement de(tag);
    de.SetVR(vr);
    de.SetByteValue(value.data(), gdcm::VL(uint32_t(value.size())));
    ds.Replace(de);
}

} // namespace

void Deidentifier::deidentifyFile(const fs::path& input, const fs::path& output) {
    const DicomStructure structure = checkDicomStructure(input.string());
    const std::string truncated = truncatedPixelData(structure);
    if (!structure.ok || !truncated.empty()) {
        throw DeidentifyError("de-identify: " + input.string() + " is not a readable DICOM file (" +
                              (structure.ok ? truncated : structure.problem) + ")");
    }
    DataSetStream stream(input.string(), structure);
    gdcm::Reader reader;
    reader.SetStream(stream);
    if (!reader.Read()) {
        throw DeidentifyError("de-identify: " + input.string() + " is not a readable DICOM file");
    }
    gdcm::File& file = reader.GetFile();
    gdcm::DataSet& ds = file.GetDataSet();
    // The profile protects attributes, not pixels: text burnt into the image
    // would reach the viewer.
    const gdcm::Tag burnedIn(0x0028, 0x0301);
    if (ds.FindDataElement(burnedIn) && valueOf(ds.GetDataElement(burnedIn)) == "YES") {
        throw DeidentifyError("de-identify: " + input.string() +
                              " has burned-in annotation (0028,0301): its pixels may identify "
                              "the patient");
    }
    protect(file, ds, *this);
    replaceText(ds, gdcm::Tag(0x0012, 0x0062), gdcm::VR::CS, "YES");
    replaceText(ds, gdcm::Tag(0x0012, 0x0063), gdcm::VR::LO,
                "BASIC APPLICATION LEVEL CONFIDENTIALITY PROFILE");

    // The file meta information names the instance and may name the sender.
    gdcm::FileMetaInformation& meta = file.GetHeader();
    const gdcm::Tag sopInstance(0x0008, 0x0018);
    if (ds.FindDataElement(sopInstance)) {
        gdcm::DataElement de(gdcm::Tag(0x0002, 0x0003));
        de.SetVR(gdcm::VR::UI);
        setUid(de, valueOf(ds.GetDataElement(sopInstance)));
        meta.Replace(de);
    }
    for (const gdcm::Tag& tag :
         {gdcm::Tag(0x0002, 0x0016), gdcm::Tag(0x0002, 0x0017), gdcm::Tag(0x0002, 0x0018),
          gdcm::Tag(0x0002, 0x0100), gdcm::Tag(0x0002, 0x0102)}) {
        meta.Remove(tag);
    }

    gdcm::Writer writer;
    writer.SetFile(file);
    writer.SetFileName(output.string().c_str());
    if (!writer.Write()) {
        throw DeidentifyError("de-identify: cannot write " + output.string());
    }
}

std::vector<fs::path> deidentifySeries(const std::vector<fs::path>& files,
                                       const fs::path& destination) {
    std::error_code error;
    if (fs::exists(destination, error)) {
        throw DeidentifyError("de-identify: " + destination.string() + " exists already");
    }
    std::random_device random;
    const fs::path staging =
        destination.parent_path() /
        (".partial-" + destination.filename().string() + "-" + std::to_string(random()));
    fs::create_directories(staging, error);
    if (error) {
        throw DeidentifyError("de-identify: cannot create " + staging.string() + ": " +
                              error.message());
    }
    Deidentifier deidentifier;
    std::vector<fs::path> written;
    try {
        for (std::size_t n = 0; n < files.size(); ++n) {
            char name[32];
            std::snprintf(name, sizeof name, "%05zu.dcm", n + 1);
            deidentifier.deidentifyFile(files[n], staging / name);
            written.push_back(destination / name);
        }
        fs::rename(staging, destination, error);
        if (error) {
            throw DeidentifyError("de-identify: cannot rename " + staging.string() + " to " +
                                  destination.string() + ": " + error.message());
        }
    } catch (...) {
        fs::remove_all(staging, error);
        throw;
    }
    return written;
}

} // namespace lucent
