#include "core/dicom/DicomStructure.h"
#include "core/dicom/MappedFile_p.h"

#include <algorithm>
#include <cstring>
#include <string_view>
#include <vector>

#include <zlib.h>

namespace lucent {
namespace {

constexpr std::uint32_t kUndefined = 0xffffffffu;
const std::string kImplicitLittle = "1.2.840.10008.1.2";
const std::string kExplicitLittle = "1.2.840.10008.1.2.1";
constexpr int kMaxDepth = 32;
// A deflated data set is inflated (in memory) to be walked, up to this size.
constexpr std::size_t kMaxInflatedBytes = std::size_t(1) << 30;

constexpr std::string_view kLongVrs[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ",
                                         "SV", "UC", "UN", "UR", "UT", "UV"};
// The rest of PS3.5's VRs. Libraries disagree on the length field of any other
// (GDCM and DCMTK read 4 bytes, allocating what they say).
constexpr std::string_view kShortVrs[] = {"AE", "AS", "AT", "CS", "DA", "DS", "DT",
                                          "FD", "FL", "IS", "LO", "LT", "PN", "SH",
                                          "SL", "SS", "ST", "TM", "UI", "UL", "US"};

bool longVr(std::string_view vr) {
    return std::find(std::begin(kLongVrs), std::end(kLongVrs), vr) != std::end(kLongVrs);
}
bool shortVr(std::string_view vr) {
    return std::find(std::begin(kShortVrs), std::end(kShortVrs), vr) != std::end(kShortVrs);
}

struct Walker {
    const unsigned char* d;
    std::size_t size;
    bool explicitVr = true;
    bool bigEndian = false;
    DicomStructure& out;
    bool paddingAllowed = true; // not inside a deflated data set, which GDCM inflates whole

    std::uint16_t u16(std::size_t at) const {
        return bigEndian ? std::uint16_t(d[at] << 8 | d[at + 1])
                         : std::uint16_t(d[at] | d[at + 1] << 8);
    }
    std::uint32_t u32(std::size_t at) const {
        return bigEndian ? std::uint32_t(d[at]) << 24 | std::uint32_t(d[at + 1]) << 16 |
                               std::uint32_t(d[at + 2]) << 8 | d[at + 3]
                         : std::uint32_t(d[at]) | std::uint32_t(d[at + 1]) << 8 |
                               std::uint32_t(d[at + 2]) << 16 | std::uint32_t(d[at + 3]) << 24;
    }
    bool fail(std::size_t at, const std::string& what) {
        out.problem = what + " at byte " + std::to_string(at);
        return false;
    }

    struct Header {
        std::uint16_t group, element;
        std::string_view vr; // empty in implicit VR
        bool sequence;       // SQ, or undefined length that must be walked as items
        std::uint32_t length;
        std::size_t valueAt;
    };

    bool header(std::size_t at, Header& h, bool forceExplicitLE = false) {
        if (at + 8 > size) {
            return fail(at, "truncated element header");
        }
        const bool saveBig = bigEndian;
        if (forceExplicitLE) {
            bigEndian = false;
        }
        h.group = u16(at);
        h.element = u16(at + 2);
        if (h.group == 0xfffe || !(explicitVr || forceExplicitLE)) {
            h.length = u32(at + 4);
            h.valueAt = at + 8;
            h.sequence = h.length == kUndefined;
        } else {
            const std::string_view vr(reinterpret_cast<const char*>(d + at + 4), 2);
            const bool isLong = longVr(vr);
            const bool known = isLong || shortVr(vr);
            if (!isLong && !known) {
                bigEndian = saveBig;
                std::string shown;
                for (const char c : vr) {
                    shown += c >= 0x20 && c < 0x7f ? std::string(1, c) : "\\x" + hex2(c);
                }
                return fail(at, "unknown value representation '" + shown + "' of element (" +
                                    hex(h.group) + "," + hex(h.element) + ")");
            }
            h.vr = vr;
            if (isLong) {
                if (at + 12 > size) {
                    bigEndian = saveBig;
                    return fail(at, "truncated element header");
                }
                h.length = u32(at + 8);
                h.valueAt = at + 12;
            } else {
                h.length = u16(at + 6);
                h.valueAt = at + 8;
            }
            h.sequence = vr == "SQ" || h.length == kUndefined;
        }
        bigEndian = saveBig;
        return true;
    }

    // Walks the items of a sequence starting at `at`, within `limit` (the end of
    // the enclosing item, or of the file), and the elements of each item: GDCM
    // parses them all. With `fragments` the items are the fragments of
    // encapsulated pixel data, whose bytes are not elements.
    bool items(std::size_t& at, std::uint32_t length, std::size_t limit, int depth,
               bool fragments) {
        if (length != kUndefined && length > limit - at) {
            return fail(at, "sequence runs past the end of " + what(limit));
        }
        const std::size_t end = length == kUndefined ? limit : at + length;
        while (at < end) {
            Header h{};
            if (!header(at, h)) {
                return false;
            }
            if (h.group != 0xfffe) {
                return fail(at, "expected a sequence item");
            }
            if (h.valueAt > end) {
                return fail(at, "item header runs past the end of its sequence");
            }
            at = h.valueAt;
            if (h.element == 0xe0dd) { // sequence delimiter
                // Its length is 0 (PS3.5 7.5); GDCM allocates any other it reads.
                return h.length == 0 || fail(at, "sequence delimiter with a length of " +
                                                     std::to_string(h.length) + " (must be 0)");
            }
            if (h.element != 0xe000) {
                return fail(at, "unexpected delimiter in a sequence");
            }
            if (h.length == kUndefined) {
                if (fragments) {
                    return fail(at, "pixel data fragment of undefined length");
                }
                if (!elements(at, end, depth + 1, true)) {
                    return false;
                }
            } else {
                if (h.length > end - at) {
                    return fail(at, "item runs past the end of its sequence or the file");
                }
                if (fragments) {
                    at += h.length;
                } else if (!elements(at, at + h.length, depth + 1, false)) {
                    return false;
                }
            }
        }
        return length != kUndefined || fail(at, "sequence without its delimiter");
    }

    // Walks elements until `end` (the end of an item of defined length, or of
    // the file) or, in items of undefined length, an item delimiter.
    bool elements(std::size_t& at, std::size_t end, int depth, bool inItem) {
        if (depth > kMaxDepth) {
            return fail(at, "sequences nested too deeply");
        }
        while (at < end) {
            if (depth == 0 && zeroHeader(at, end)) {
                // Padding after the data set, or no DICOM after it.
                return onlyZerosFrom(at, end) || dataAfterZeros(at, end);
            }
            Header h{};
            if (!header(at, h)) {
                return false;
            }
            if (h.valueAt > end) {
                return fail(at, "element header runs past the end of " + what(end));
            }
            if (h.group == 0xfffe && h.element == 0xe00d) {
                at = h.valueAt;
                if (h.length != 0) {
                    return fail(at, "item delimiter with a length of " + std::to_string(h.length) +
                                        " (must be 0)");
                }
                return inItem || fail(at, "item delimiter outside an item");
            }
            if (h.group == 0xfffe) {
                // Items and sequence delimiters belong to sequences; GDCM asserts on
                // one it meets among the elements (fuzz_dicom).
                return fail(at,
                            "(FFFE," + hex(h.element) + ") among the elements, outside a sequence");
            }
            const std::size_t start = at;
            at = h.valueAt;
            const bool pixelData = depth == 0 && h.group == 0x7fe0 && h.element == 0x0010;
            if (h.length == kUndefined && !h.vr.empty() && h.vr != "SQ" && h.vr != "UN" &&
                !(pixelData && (h.vr == "OB" || h.vr == "OW"))) {
                // GDCM asserts on an undefined length of any other VR.
                return fail(start, "element (" + hex(h.group) + "," + hex(h.element) + ") of VR '" +
                                       std::string(h.vr) + "' has an undefined length");
            }
            const bool pixelTag = h.group == 0x7fe0 && h.element == 0x0010;
            if (pixelTag && !h.vr.empty() && h.vr != "OB" && h.vr != "OW" && h.vr != "UN") {
                // GDCM asserts on Pixel Data of another VR (SQ in big endian; SQ
                // inside an item, fuzz_dicom), at any depth.
                return fail(start, "Pixel Data (7FE0,0010) has VR '" + std::string(h.vr) +
                                       "', not OB or OW");
            }
            if (pixelTag && depth > 0 && h.length == kUndefined) {
                return fail(start, "Pixel Data (7FE0,0010) of undefined length inside an item");
            }
            if (pixelData) {
                out.hasPixelData = true;
                out.pixelOffset = at;
                out.encapsulated = h.length == kUndefined;
                out.pixelLength = out.encapsulated ? 0 : h.length;
                if (out.encapsulated) {
                    if (!items(at, kUndefined, end, depth, true)) {
                        return fail(start, "encapsulated pixel data: " + out.problem);
                    }
                    continue;
                }
                if (h.length > size - at) {
                    return true; // the caller reports the pixel data as truncated
                }
                // What follows (padding, private trailers) is walked too: GDCM
                // reads it whole, allocating the lengths it declares.
                at += h.length;
                continue;
            }
            if (h.sequence) {
                // A sequence written as UN of undefined length (a private one, by a
                // converter that did not know it) holds implicit VR items (CP-246).
                // GDCM reads them in the file's byte order, so the walk does too.
                const bool saveExplicit = explicitVr;
                explicitVr = explicitVr && !(h.vr == "UN" && h.length == kUndefined);
                const bool walked = items(at, h.length, end, depth, false);
                explicitVr = saveExplicit;
                if (!walked) {
                    return false;
                }
                continue;
            }
            if (h.length > end - at) {
                return fail(start, "element (" + hex(h.group) + "," + hex(h.element) +
                                       ") runs past the end of " + what(end));
            }
            at += h.length;
        }
        return !inItem || fail(at, "item without its delimiter");
    }

    std::string what(std::size_t end) const { return end == size ? "the file" : "its item"; }

    // Where the next top-level element would start, its header is all zeros (or
    // the file ends in fewer than 8 zero bytes): no data set has such an element.
    // DCMTK rewrites zero padding as (0000,0000) UL of length 4, an element.
    bool zeroHeader(std::size_t at, std::size_t end) const {
        const std::size_t n = std::min<std::size_t>(8, end - at);
        return std::all_of(d + at, d + at + n, [](unsigned char c) { return c == 0; });
    }

    // Zero bytes after the last element (CD/DVD media, some archives pad files
    // so) end the data set, as DCMTK and GDCM read it, with a warning.
    bool onlyZerosFrom(std::size_t at, std::size_t end) {
        if (!paddingAllowed ||
            std::any_of(d + at, d + end, [](unsigned char c) { return c != 0; })) {
            return false;
        }
        out.dataSetEnd = at;
        out.warnings.push_back(std::to_string(end - at) +
                               " zero bytes after the last element of the data set (from byte " +
                               std::to_string(at) + ") ignored as padding");
        return true;
    }

    // Zeros that are no element, then other bytes: no DICOM after the data set.
    bool dataAfterZeros(std::size_t at, std::size_t end) {
        const unsigned char* nonZero =
            std::find_if(d + at, d + end, [](unsigned char c) { return c != 0; });
        if (nonZero == d + end) { // padding where it cannot be (paddingAllowed)
            return fail(at, std::to_string(end - at) +
                                " zero bytes after the last element, inside the deflated data");
        }
        return fail(static_cast<std::size_t>(nonZero - d),
                    "data after " + std::to_string(nonZero - (d + at)) +
                        " zero bytes that follow the last element of the data set");
    }

    static std::string hex(std::uint16_t v) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "%04X", v);
        return buf;
    }
    static std::string hex2(char c) {
        char buf[4];
        std::snprintf(buf, sizeof buf, "%02X", static_cast<unsigned char>(c));
        return buf;
    }
};

// The data set of a Deflated Explicit VR Little Endian file: raw deflate (RFC 1951).
bool inflateDataSet(const unsigned char* d, std::size_t size, std::vector<unsigned char>& out,
                    std::string& problem) {
    z_stream z{};
    if (inflateInit2(&z, -MAX_WBITS) != Z_OK) {
        problem = "cannot inflate the deflated data set (zlib)";
        return false;
    }
    z.next_in = const_cast<unsigned char*>(d);
    z.avail_in = static_cast<uInt>(std::min<std::size_t>(size, 1u << 30));
    out.resize(std::max<std::size_t>(size * 4, 4096));
    int status = Z_OK;
    while (status == Z_OK) {
        if (z.total_out == out.size()) {
            if (out.size() >= kMaxInflatedBytes) {
                problem = "deflated data set inflates to more than " +
                          std::to_string(kMaxInflatedBytes >> 20) + " MiB";
                inflateEnd(&z);
                return false;
            }
            out.resize(std::min(out.size() * 2, kMaxInflatedBytes));
        }
        z.next_out = out.data() + z.total_out;
        z.avail_out = static_cast<uInt>(out.size() - z.total_out);
        status = inflate(&z, Z_NO_FLUSH);
    }
    out.resize(z.total_out);
    inflateEnd(&z);
    if (status != Z_STREAM_END && !(status == Z_BUF_ERROR && z.avail_in == 0)) {
        problem = std::string("deflated data set is corrupt (zlib: ") +
                  (z.msg != nullptr ? z.msg : "error " + std::to_string(status)) + ")";
        return false;
    }
    return true;
}

// True when the element at `at` carries a VR of PS3.5 after its tag: explicit VR.
bool looksExplicit(const unsigned char* d, std::size_t at) {
    const std::string_view vr(reinterpret_cast<const char*>(d + at + 4), 2);
    return longVr(vr) || shortVr(vr);
}

// A meta group length (0002,0000) past the group's last element: GDCM reads
// everything up to it as meta elements, and asserts on a sequence, an undefined
// length or bytes that are no explicit VR element there (fuzz_dicom). What lies
// there must read as the meta group's elements do.
bool metaOvershootReadable(Walker& w, std::size_t at, std::uint64_t metaEnd) {
    for (std::size_t p = at; p < metaEnd;) {
        Walker::Header h{};
        if (p + 8 > w.size || !w.header(p, h, true) || h.vr == "SQ" || h.length == kUndefined ||
            h.length > w.size - h.valueAt) {
            w.out.problem = "file meta information group length (0002,0000) says the group ends "
                            "at byte " +
                            std::to_string(metaEnd) + ", past its last element at byte " +
                            std::to_string(at) + ", over bytes that are no meta element (at byte " +
                            std::to_string(p) + ")";
            return false;
        }
        p = h.valueAt + h.length;
    }
    return true;
}

// File meta information: group 0002 after the preamble, always explicit little
// endian. Its group length (0002,0000) may be wrong or absent: DCMTK and GDCM
// read the group to its last element, and so does this.
bool readFileMeta(Walker& w, std::size_t& at) {
    DicomStructure& out = w.out;
    const std::size_t size = w.size;
    std::uint64_t metaEnd = 0; // from (0002,0000) when present
    int lastElement = -1;
    while (at < size && (at + 8 > size || w.u16(at) == 0x0002)) {
        Walker::Header h{};
        if (!w.header(at, h, true) || h.length == kUndefined || h.length > size - h.valueAt) {
            out.problem = "truncated file meta information at byte " + std::to_string(at);
            return false;
        }
        if (h.vr == "SQ") { // GDCM asserts on a sequence here
            out.problem = "file meta information element (0002," + Walker::hex(h.element) +
                          ") is a sequence, at byte " + std::to_string(at);
            return false;
        }
        if (h.element <= lastElement) { // GDCM reads another copy than the walk (fuzz_dicom)
            out.problem = "file meta information element (0002," + Walker::hex(h.element) +
                          ") repeated or out of order, at byte " + std::to_string(at);
            return false;
        }
        lastElement = h.element;
        if (h.element == 0x0000 && h.length == 4) {
            metaEnd = h.valueAt + 4 + std::uint64_t(w.u32(h.valueAt));
            out.metaGroupLengthAt = h.valueAt;
        }
        if (h.element == 0x0010) {
            out.metaSyntaxAt = at;
            std::string uid(reinterpret_cast<const char*>(w.d + h.valueAt), h.length);
            while (!uid.empty() && (uid.back() == '\0' || uid.back() == ' ')) {
                uid.pop_back();
            }
            out.transferSyntax = uid;
        }
        at = h.valueAt + h.length;
    }
    if (metaEnd > at && !metaOvershootReadable(w, at, metaEnd)) {
        return false;
    }
    out.metaGroupLengthPast = metaEnd > at;
    out.metaGroupLengthWrong = metaEnd != 0 && metaEnd != at;
    out.metaEnd = at;
    if (metaEnd != 0 && metaEnd != at) {
        out.warnings.push_back("file meta information group length (0002,0000) says the group "
                               "ends at byte " +
                               std::to_string(metaEnd) + "; its last element ends at byte " +
                               std::to_string(at) + " (read to its last element)");
    }
    if (at >= size) {
        out.problem = "no data set after the file meta information";
        return false;
    }
    if (std::all_of(w.d + at, w.d + size, [](unsigned char c) { return c == 0; })) {
        out.problem = "no data set after the file meta information, only " +
                      std::to_string(size - at) + " zero bytes from byte " + std::to_string(at);
        return false;
    }
    if (out.transferSyntax.empty()) {
        out.problem = "file meta information without a transfer syntax";
        return false;
    }
    return true;
}

// A data set in implicit VR under a meta header that says Explicit VR Little
// Endian is read as implicit, as GDCM and pydicom do (DCMTK with
// --read-xfer-detect). The other way round GDCM cannot read, so it is refused.
bool checkDataSetEncoding(Walker& w, std::size_t at) {
    DicomStructure& out = w.out;
    if (at + 8 > w.size) {
        return true; // the walk reports the truncation
    }
    if (std::all_of(w.d + at, w.d + at + 8, [](unsigned char c) { return c == 0; })) {
        return true; // no element: the walk reports it
    }
    const bool explicitVr = looksExplicit(w.d, at);
    const std::string element = "(" + Walker::hex(w.u16(at)) + "," + Walker::hex(w.u16(at + 2)) +
                                ") at byte " + std::to_string(at);
    if (out.transferSyntax == kExplicitLittle && !explicitVr) {
        out.transferSyntax = kImplicitLittle;
        out.metaSyntaxWrong = true;
        out.warnings.push_back("the file meta information says Explicit VR Little Endian, but the "
                               "data set is in implicit VR (element " +
                               element + "): read as Implicit VR Little Endian");
    }
    if (out.metaGroupLengthPast && (out.transferSyntax != kExplicitLittle || !explicitVr)) {
        // GDCM's data set would start where the group length says, in bytes that
        // were walked in another encoding.
        out.problem = "file meta information group length (0002,0000) runs into a data set "
                      "that is not in Explicit VR Little Endian (element " +
                      element + ")";
        return false;
    }
    if (out.transferSyntax == kImplicitLittle && explicitVr) {
        out.problem = "the file meta information says Implicit VR Little Endian, but the data set "
                      "is in explicit VR (element " +
                      element + " has the VR '" +
                      std::string(reinterpret_cast<const char*>(w.d + at + 4), 2) + "')";
        return false;
    }
    return true;
}

} // namespace

DicomStructure checkDicomStructure(const std::string& file) {
    DicomStructure out;
    const MappedFile f(file);
    if (!f.opened()) {
        out.problem = "cannot open for reading";
        return out;
    }
    const unsigned char* d = f.data();
    const std::size_t size = f.size();
    if (size == 0) {
        out.problem = "empty file";
        return out;
    }
    out.dataSetEnd = size;
    out.fileSize = size;
    Walker w{d, size, true, false, out};
    std::size_t at = 0;
    if (size >= 132 && std::memcmp(d + 128, "DICM", 4) == 0) {
        at = 132;
        if (!readFileMeta(w, at) || !checkDataSetEncoding(w, at)) {
            return out;
        }
    } else {
        // No preamble: a bare data set, accepted only if it starts like one.
        if (size < 8 || !(d[0] == 0x08 && d[1] == 0x00)) {
            out.problem = "not a DICOM file";
            return out;
        }
        w.explicitVr = looksExplicit(d, 0);
        out.transferSyntax = w.explicitVr ? kExplicitLittle : kImplicitLittle;
    }
    const std::string& ts = out.transferSyntax;
    if (ts == "1.2.840.10008.1.2.1.99") {
        // Deflated: GDCM inflates and parses the data set; it is walked here
        // first, inflated. Offsets into it mean nothing in the file, so the
        // pixel data must be whole (nobody compares its length later).
        std::vector<unsigned char> inflated;
        if (!inflateDataSet(d + at, size - at, inflated, out.problem)) {
            return out;
        }
        DicomStructure inner;
        Walker iw{inflated.data(), inflated.size(), true, false, inner, false};
        std::size_t innerAt = 0;
        if (!iw.elements(innerAt, inflated.size(), 0, false)) {
            out.problem = "deflated data set: " + inner.problem;
            return out;
        }
        if (inner.hasPixelData && !inner.encapsulated &&
            inner.pixelLength > inflated.size() - inner.pixelOffset) {
            out.problem = "deflated data set: Pixel Data (7FE0,0010) runs past its end";
            return out;
        }
        for (const std::string& warning : inner.warnings) {
            out.warnings.push_back("deflated data set: " + warning);
        }
        out.ok = true;
        return out;
    }
    w.explicitVr = ts != kImplicitLittle;
    w.bigEndian = ts == "1.2.840.10008.1.2.2";
    if (!w.elements(at, size, 0, false)) {
        return out;
    }
    out.ok = true;
    return out;
}

std::string truncatedPixelData(const DicomStructure& structure) {
    if (!structure.hasPixelData || structure.encapsulated ||
        structure.pixelOffset > structure.fileSize ||
        structure.pixelLength <= structure.fileSize - structure.pixelOffset) {
        return {};
    }
    return "truncated pixel data: Pixel Data (7FE0,0010) declares " +
           std::to_string(structure.pixelLength) + " bytes, the file ends " +
           std::to_string(structure.fileSize - structure.pixelOffset) + " bytes after its start";
}

} // namespace lucent
