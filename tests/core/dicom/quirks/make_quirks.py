#!/usr/bin/env python3
"""Makes the DICOM quirks corpus of test_dicom_quirks in OUT_DIR from the real
files of DATA_DIR (../shared/data): each case is a real file re-encoded by
DCMTK (dcmconv, dcmodify) and, where no DCMTK option makes the quirk, changed by
a few bytes (an element's length, a UID, a group length). No DICOM is written
by hand. OUT_DIR/cases.json lists the cases: name, file, source, what the quirk
is, and, where Lucent deliberately differs from dcmdump, why.
Usage: make_quirks.py OUT_DIR DATA_DIR"""
import json
import pathlib
import shutil
import struct
import subprocess
import sys

PHILIPS = "dcm_qa_ct/Philips_S21570/S2010/I10"  # explicit LE, sequences, private tags
GE = "dcmqi_ct3slice/01.dcm"  # implicit LE, group lengths, private groups
MR = "nema_wg04/MR1/MR1_UNC.dcm"  # explicit LE MR
RLE = "nema_wg04/CT1/CT1_RLE.dcm"  # RLE Lossless, decoded by GDCM in lucent-frame-decoder
RLE_PIXELS = "nema_wg04/CT1/CT1_UNC.dcm"  # the same pixels, uncompressed


def run(*args):
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


class Edit:
    """A few bytes of a real file changed in place. Elements are found by their
    tag and, in explicit VR, their VR, at the top level before Pixel Data."""

    def __init__(self, path, explicit=True):
        self.path = pathlib.Path(path)
        self.data = bytearray(self.path.read_bytes())
        self.explicit = explicit

    def find(self, group, element, vr=None):
        key = struct.pack("<HH", group, element) + (vr.encode() if vr else b"")
        at = self.data.find(key, 132 if group != 2 else 128)
        if at < 0:
            raise SystemExit(f"{self.path}: ({group:04X},{element:04X}) not found")
        return at

    def header(self, at, group):
        """(offset of the length field, its size, header size) of the element at `at`."""
        if group == 2 or self.explicit:
            return at + 6, 2, 8  # the VRs edited here have 2-byte lengths
        return at + 4, 4, 8

    def length(self, at, group):
        field, size, _ = self.header(at, group)
        return int.from_bytes(self.data[field:field + size], "little")

    def set_length(self, at, group, value):
        field, size, _ = self.header(at, group)
        self.data[field:field + size] = value.to_bytes(size, "little")

    def add_to_group_length(self, group, delta):
        key = struct.pack("<HH", group, 0) + (b"UL" if group == 2 or self.explicit else b"")
        at = self.data.find(key, 128)
        if at < 0:
            return
        value_at = at + 8
        value = struct.unpack_from("<I", self.data, value_at)[0]
        struct.pack_into("<I", self.data, value_at, value + delta)

    def replace_value(self, group, element, vr, value):
        at = self.find(group, element, vr if (group == 2 or self.explicit) else None)
        _, _, head = self.header(at, group)
        old = self.length(at, group)
        self.data[at + head:at + head + old] = value
        self.set_length(at, group, len(value))
        self.add_to_group_length(group, len(value) - old)

    def save(self, path):
        pathlib.Path(path).write_bytes(bytes(self.data))


def copy(src, dst):
    shutil.copyfile(src, dst)
    dst.chmod(0o644)


def odd_length(src, dst, explicit):
    """(0008,0070) Manufacturer one byte shorter (its padding, or its last letter): an odd
    length."""
    e = Edit(src, explicit)
    at = e.find(0x0008, 0x0070, "LO" if explicit else None)
    n = e.length(at, 0x0008)
    _, _, head = e.header(at, 0x0008)
    if n % 2:
        raise SystemExit(f"{src}: Manufacturer has an odd length already")
    del e.data[at + head + n - 1]
    e.set_length(at, 0x0008, n - 1)
    e.add_to_group_length(0x0008, -1)
    e.save(dst)


def private_sequence_as_un(philips, out, dst):
    """CP-246: a private sequence written as UN of undefined length, its items in
    implicit VR. DCMTK writes the private sequence (ReferencedImageSequence's
    bytes under the private tag (0009,1140)) in implicit VR, then in explicit VR;
    the explicit file's SQ is replaced by the UN header and the implicit items."""
    delimiter = bytes.fromhex("feffdde000000000")
    tag = struct.pack("<HH", 0x0009, 0x1140)
    implicit, explicit = out / "cp246-implicit.tmp", out / "cp246-explicit.tmp"
    run("dcmconv", "+ti", "-e", str(philips), str(implicit))
    e = Edit(implicit, explicit=False)
    at = e.find(0x0008, 0x1140)
    e.data[at:at + 4] = tag
    e.save(implicit)
    run("dcmconv", "+te", "-e", str(implicit), str(explicit))
    items = e.data[at + 8:e.data.index(delimiter, at) + 8]
    x = Edit(explicit)
    start = x.find(0x0009, 0x1140, "SQ")
    end = x.data.index(delimiter, start) + 8
    x.data[start:end] = tag + b"UN\0\0" + b"\xff" * 4 + items
    x.save(dst)
    implicit.unlink()
    explicit.unlink()


def cases(data, out):
    philips, ge, mr = data / PHILIPS, data / GE, data / MR
    rle, rle_pixels = data / RLE, data / RLE_PIXELS
    made = []

    def case(name, source, what, divergence=None, dcmdump_options=None, pixels_of=None):
        entry = {"name": name, "file": f"{name}.dcm", "source": str(source.relative_to(data)),
                 "what": what}
        if pixels_of:  # compressed: DCMTK's reference pixels are those of this file
            entry["pixels_of"] = str(pixels_of.relative_to(data))
        if divergence:
            entry["divergence"] = divergence
        if dcmdump_options:
            entry["dcmdump_options"] = dcmdump_options
        made.append(entry)
        return out / f"{name}.dcm"

    f = case("trailing-zeros", mr, "2.5 MB of zero bytes after the last element (CD/DVD media)")
    f.write_bytes(mr.read_bytes() + bytes(2_500_000))
    run("dcmconv", str(f), str(case(
        "trailing-zeros-rewritten", mr,
        "the padded file rewritten by dcmconv: (0000,0000) UL 0 first in the data set")))
    f = case("trailing-zeros-implicit", ge, "64 KiB of zero bytes after Pixel Data, implicit VR")
    f.write_bytes(ge.read_bytes() + bytes(65536))
    f = case("trailing-zeros-odd-count", mr, "3 zero bytes after the last element",
             "zero bytes after the data set are ignored, any number of them (GDCM reads it too); "
             "dcmdump reads zeros as 8-byte elements (0000,0000) and ends early on the last 3")
    f.write_bytes(mr.read_bytes() + bytes(3))
    f = case("trailing-zeros-after-rle", rle, "4 KiB of zero bytes after RLE pixel data",
             pixels_of=rle_pixels)
    f.write_bytes(rle.read_bytes() + bytes(4096))
    f = case("trailing-7-zeros-after-rle", rle, "7 zero bytes after RLE pixel data (GDCM's "
             "full read aborts on these)", "as trailing-zeros-odd-count: dcmdump ends early on "
             "the last 7 bytes", pixels_of=rle_pixels)
    f.write_bytes(rle.read_bytes() + bytes(7))
    f = case("trailing-zeros-then-data", mr, "zero bytes, then bytes that are no element")
    f.write_bytes(mr.read_bytes() + bytes(4096) + b"LUCENT")
    f = case("trailing-garbage", mr, "bytes that are no element after the last one")
    f.write_bytes(mr.read_bytes() + b"\x01\x02\x03\x04garbage!")

    run("dcmconv", "-F", str(philips), str(case("bare-dataset-explicit", philips,
                                                   "no preamble, no DICM, no meta: explicit VR")))
    run("dcmconv", "-F", "+ti", str(philips),
        str(case("bare-dataset-implicit", philips, "no preamble, no DICM, no meta: implicit VR")))

    run("dcmconv", "+g", str(philips),
        str(case("group-lengths-present", philips, "group length elements in every group")))
    run("dcmconv", "-g", str(ge), str(case("group-lengths-absent", ge,
                                           "no group length element anywhere (implicit VR)")))
    tmp = out / "with-group-lengths.tmp"
    run("dcmconv", "+g", str(philips), str(tmp))
    e = Edit(tmp)
    e.add_to_group_length(0x0008, 100)
    e.save(case("group-length-wrong", philips, "(0008,0000) says 100 bytes more than group 0008"))
    e = Edit(philips)
    e.add_to_group_length(0x0002, 6)
    e.save(case("meta-group-length-wrong", philips, "(0002,0000) says 6 bytes more than the meta"))
    e = Edit(philips)
    e.add_to_group_length(0x0002, -6)
    e.save(case("meta-group-length-short", philips, "(0002,0000) says 6 bytes less than the meta"))
    e = Edit(philips)
    at = e.find(0x0002, 0x0000, "UL")
    del e.data[at:at + 12]
    e.save(case("meta-group-length-absent", philips, "file meta information without (0002,0000)"))
    tmp.unlink()

    odd_length(philips, case("odd-length-explicit", philips, "an odd value length (0008,0070)"),
               True)
    odd_length(ge, case("odd-length-implicit", ge, "an odd value length (0008,0070), implicit VR"),
               False)

    run("dcmconv", "+ti", "-e", str(philips), str(case(
        "undefined-length-sequences-implicit", philips,
        "sequences and items of undefined length, implicit VR")))
    run("dcmconv", "-e", str(philips), str(case(
        "undefined-length-sequences-explicit", philips,
        "sequences and items of undefined length, explicit VR")))
    run("dcmconv", "+te", str(ge), str(case(
        "private-elements-as-un", ge, "private elements of unknown VR written as UN")))

    private_sequence_as_un(philips, out, case(
        "private-sequence-as-un", philips,
        "a private sequence as UN of undefined length, its items in implicit VR (CP-246)"))

    f = case("ds-is-quirks", philips,
             "DS and IS with leading '+', inner and trailing spaces, exponents")
    copy(philips, f)
    run("dcmodify", "-nb", "-m", r"(0028,0030)=+4.51171875E-01 \ 0.451171875 ",
        "-m", "(0020,0013)=+1 ", "-m", "(0018,0050)=5.0e0 ",
        "-m", r"(0020,0032)=-1.155E+2\-1.85 \+6.9621e2", str(f))

    e = Edit(ge, explicit=False)
    e.replace_value(0x0002, 0x0010, "UI", b"1.2.840.10008.1.2.1\x00")
    # Compared with dcmdump --read-xfer-detect: DCMTK detects the data set's
    # encoding only when asked; GDCM detects this one by itself.
    e.save(case("meta-explicit-data-implicit", ge,
                "the meta says Explicit VR Little Endian, the data set is implicit VR",
                dcmdump_options=["-td"]))
    e = Edit(philips)
    e.replace_value(0x0002, 0x0010, "UI", b"1.2.840.10008.1.2\x00")
    e.save(case("meta-implicit-data-explicit", philips,
                "the meta says Implicit VR Little Endian, the data set is explicit VR",
                "GDCM, which reads Lucent's headers, cannot read it (gdcminfo fails): refused "
                "with a message that names both encodings; dcmdump without -td refuses it too",
                dcmdump_options=["-td"]))

    f = case("imager-pixel-spacing", philips,
             "no PixelSpacing (0028,0030); ImagerPixelSpacing (0018,1164) present")
    copy(philips, f)
    run("dcmodify", "-nb", "-e", "(0028,0030)", "-i", r"(0018,1164)=0.451171875\0.451171875",
        str(f))

    run("dcmconv", "+tb", str(philips),
        str(case("big-endian", philips, "Explicit VR Big Endian (retired)")))
    run("dcmconv", "+td", str(ge), str(case("deflated", ge, "Deflated Explicit VR Little Endian")))
    return made


def main():
    out = pathlib.Path(sys.argv[1])
    data = pathlib.Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    made = []
    if all((data / p).is_file() for p in (PHILIPS, GE, MR, RLE, RLE_PIXELS)):
        made = cases(data, out)
    (out / "cases.json").write_text(json.dumps(made, indent=1) + "\n")


if __name__ == "__main__":
    main()
