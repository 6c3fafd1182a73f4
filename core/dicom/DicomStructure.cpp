#include "core/dicom/DicomStructure.h"

#include <cstring>
#include <string_view>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace lucent {
namespace {

constexpr std::uint32_t kUndefined = 0xffffffffu;
constexpr int kMaxDepth = 32;

// A read-only view of a whole file, unmapped on destruction.
class MappedFile {
public:
    explicit MappedFile(const std::string& path) {
        const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) {
            return;
        }
        struct stat st {};
        if (::fstat(fd, &st) == 0 && st.st_size > 0) {
            void* p = ::mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ, MAP_PRIVATE,
                             fd, 0);
            if (p != MAP_FAILED) {
                data_ = static_cast<const unsigned char*>(p);
                size_ = static_cast<std::size_t>(st.st_size);
            }
        }
        opened_ = true;
        ::close(fd);
    }
    ~MappedFile() {
        if (data_ != nullptr) {
            ::munmap(const_cast<unsigned char*>(data_), size_);
        }
    }
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;
    bool opened() const { return opened_; }
    const unsigned char* data() const { return data_; }
    std::size_t size() const { return size_; }

private:
    const unsigned char* data_ = nullptr;
    std::size_t size_ = 0;
    bool opened_ = false;
};

struct Walker {
    const unsigned char* d;
    std::size_t size;
    bool explicitVr = true;
    bool bigEndian = false;
    DicomStructure& out;

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
        bool sequence; // SQ, or undefined length that must be walked as items
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
            static constexpr std::string_view longVrs[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ",
                                                           "SV", "UC", "UN", "UR", "UT", "UV"};
            bool isLong = false;
            for (std::string_view v : longVrs) {
                isLong = isLong || v == vr;
            }
            if (vr[0] < 'A' || vr[0] > 'Z' || vr[1] < 'A' || vr[1] > 'Z') {
                bigEndian = saveBig;
                return fail(at, "invalid value representation");
            }
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

    // Walks the items of a sequence (or encapsulated fragments) starting at `at`.
    bool items(std::size_t& at, std::uint32_t length, int depth) {
        const std::size_t end = length == kUndefined ? size : at + length;
        if (end > size) {
            return fail(at, "sequence runs past the end of the file");
        }
        while (at < end) {
            Header h{};
            if (!header(at, h)) {
                return false;
            }
            if (h.group != 0xfffe) {
                return fail(at, "expected a sequence item");
            }
            at = h.valueAt;
            if (h.element == 0xe0dd) { // sequence delimiter
                return true;
            }
            if (h.element != 0xe000) {
                return fail(at, "unexpected delimiter in a sequence");
            }
            if (h.length == kUndefined) {
                if (!elements(at, size, depth + 1, true)) {
                    return false;
                }
            } else {
                if (h.length > size - at) {
                    return fail(at, "item runs past the end of the file");
                }
                at += h.length;
            }
        }
        return length != kUndefined || fail(at, "sequence without its delimiter");
    }

    // Walks elements until `end`, an item delimiter (in items), or top-level Pixel Data.
    bool elements(std::size_t& at, std::size_t end, int depth, bool inItem) {
        if (depth > kMaxDepth) {
            return fail(at, "sequences nested too deeply");
        }
        while (at < end) {
            Header h{};
            if (!header(at, h)) {
                return false;
            }
            if (h.group == 0xfffe && h.element == 0xe00d) {
                at = h.valueAt;
                return inItem || fail(at, "item delimiter outside an item");
            }
            const std::size_t start = at;
            at = h.valueAt;
            const bool pixelData = depth == 0 && h.group == 0x7fe0 && h.element == 0x0010;
            if (pixelData) {
                out.hasPixelData = true;
                out.pixelOffset = at;
                out.encapsulated = h.length == kUndefined;
                out.pixelLength = out.encapsulated ? 0 : h.length;
                if (!out.encapsulated) {
                    return true; // the caller compares the length with what the image needs
                }
                return items(at, kUndefined, depth) ||
                       fail(start, "encapsulated pixel data: " + out.problem);
            }
            if (h.sequence) {
                if (!items(at, h.length, depth)) {
                    return false;
                }
                continue;
            }
            if (h.length > size - at) {
                return fail(start, "element (" + hex(h.group) + "," + hex(h.element) +
                                       ") runs past the end of the file");
            }
            at += h.length;
        }
        return !inItem || fail(at, "item without its delimiter");
    }

    static std::string hex(std::uint16_t v) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "%04X", v);
        return buf;
    }
};

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
    Walker w{d, size, true, false, out};
    std::size_t at = 0;
    if (size >= 132 && std::memcmp(d + 128, "DICM", 4) == 0) {
        // File meta information: group 0002, always explicit little endian.
        at = 132;
        std::uint64_t metaEnd = 0; // from (0002,0000) when present
        while (at < size && (at + 8 > size || w.u16(at) == 0x0002)) {
            Walker::Header h{};
            if (!w.header(at, h, true) || h.length == kUndefined || h.length > size - h.valueAt) {
                out.problem = "truncated file meta information at byte " + std::to_string(at);
                return out;
            }
            if (h.element == 0x0000 && h.length == 4) {
                metaEnd = h.valueAt + 4 + std::uint64_t(w.u32(h.valueAt));
            }
            if (h.element == 0x0010) {
                std::string uid(reinterpret_cast<const char*>(d + h.valueAt), h.length);
                while (!uid.empty() && (uid.back() == '\0' || uid.back() == ' ')) {
                    uid.pop_back();
                }
                out.transferSyntax = uid;
            }
            at = h.valueAt + h.length;
        }
        if (metaEnd != 0 && metaEnd != at) {
            out.problem = metaEnd > size ? "truncated file meta information"
                                         : "file meta information group length does not match";
            return out;
        }
        if (at >= size) {
            out.problem = "no data set after the file meta information";
            return out;
        }
        if (out.transferSyntax.empty()) {
            out.problem = "file meta information without a transfer syntax";
            return out;
        }
    } else {
        // No preamble: a bare data set, accepted only if it starts like one.
        if (size < 8 || !(d[0] == 0x08 && d[1] == 0x00)) {
            out.problem = "not a DICOM file";
            return out;
        }
        w.explicitVr = d[4] >= 'A' && d[4] <= 'Z' && d[5] >= 'A' && d[5] <= 'Z';
        out.transferSyntax = w.explicitVr ? "1.2.840.10008.1.2.1" : "1.2.840.10008.1.2";
    }
    const std::string& ts = out.transferSyntax;
    if (ts == "1.2.840.10008.1.2.1.99") {
        out.ok = true; // deflated: the data set is compressed; GDCM inflates and parses it
        return out;
    }
    w.explicitVr = ts != "1.2.840.10008.1.2";
    w.bigEndian = ts == "1.2.840.10008.1.2.2";
    if (!w.elements(at, size, 0, false)) {
        return out;
    }
    out.ok = true;
    return out;
}

} // namespace lucent
