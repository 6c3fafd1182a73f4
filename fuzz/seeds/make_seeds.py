#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz harnesses (fuzz/corpus/<harness>/; the DICOM ones are
not committed, see main)
and the protocol dictionary (fuzz/dict/protocol.dict). Everything is made here:
tiny synthetic images (no patient data), messages from docs/protocol.md. Compressed
DICOM variants are made from the synthetic image with DCMTK's and GDCM's command
line tools (packaging/install-deps.sh installs them). Deterministic: rerunning it
rewrites the same bytes. Real data (../shared/data) is never copied here;
packaging/fuzz.sh adds it as extra seeds at run time."""
import gzip
import io
import json
import pathlib
import re
import shutil
import struct
import subprocess
import sys
import tarfile
import tempfile
import zlib

FUZZ = pathlib.Path(__file__).resolve().parent.parent
ROOT = FUZZ.parent
CORPUS = FUZZ / "corpus"

EXPLICIT_LE = "1.2.840.10008.1.2.1"
IMPLICIT_LE = "1.2.840.10008.1.2"
EXPLICIT_BE = "1.2.840.10008.1.2.2"
RLE = "1.2.840.10008.1.2.5"
LONG_VRS = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC", "UN", "UR", "UT", "UV"}
UNDEFINED = 0xFFFFFFFF


def pad(vr, value):
    if len(value) % 2:
        value += b"\0" if vr in ("UI", "OB", "UN") else b" "
    return value


class Writer:
    """Data elements in one transfer syntax: explicit/implicit VR, either byte order."""

    def __init__(self, explicit=True, big=False):
        self.explicit, self.big = explicit, big
        self.e = ">" if big else "<"

    def element(self, group, elem, vr, value, undefined=False):
        if isinstance(value, str):
            value = value.encode("ascii")
        value = pad(vr, value)
        length = UNDEFINED if undefined else len(value)
        head = struct.pack(self.e + "HH", group, elem)
        if group == 0xFFFE or not self.explicit:
            return head + struct.pack(self.e + "I", length) + value
        if vr in LONG_VRS:
            return head + vr.encode() + b"\0\0" + struct.pack(self.e + "I", length) + value
        return head + vr.encode() + struct.pack(self.e + "H", length) + value

    def us(self, group, elem, *values):
        return self.element(group, elem, "US", struct.pack(self.e + "H" * len(values), *values))

    def sequence(self, group, elem, items, undefined=True):
        body = b""
        for item in items:
            if undefined:
                body += struct.pack(self.e + "HHI", 0xFFFE, 0xE000, UNDEFINED) + item
                body += struct.pack(self.e + "HHI", 0xFFFE, 0xE00D, 0)
            else:
                body += struct.pack(self.e + "HHI", 0xFFFE, 0xE000, len(item)) + item
        if undefined:
            body += struct.pack(self.e + "HHI", 0xFFFE, 0xE0DD, 0)
        return self.element(group, elem, "SQ", body, undefined=undefined)


def meta(syntax, sop_class, sop_instance):
    w = Writer()
    body = (w.element(0x0002, 0x0001, "OB", b"\0\1") + w.element(0x0002, 0x0002, "UI", sop_class)
            + w.element(0x0002, 0x0003, "UI", sop_instance) + w.element(0x0002, 0x0010, "UI", syntax)
            + w.element(0x0002, 0x0012, "UI", "1.2.826.0.1.3680043.9.7433.1"))
    return b"\0" * 128 + b"DICM" + w.element(0x0002, 0x0000, "UL", struct.pack("<I", len(body))) + body


CT_CLASS = "1.2.840.10008.5.1.4.1.1.2"
SERIES = "1.2.826.0.1.3680043.9.7433.2.1"
STUDY = "1.2.826.0.1.3680043.9.7433.2"


def image_header(w, sop_class, sop, rows=8, cols=8, bits=16, modality="CT", frames=None,
                 geometry=True):
    out = (w.element(0x0008, 0x0008, "CS", "ORIGINAL\\PRIMARY\\AXIAL")
           + w.element(0x0008, 0x0016, "UI", sop_class) + w.element(0x0008, 0x0018, "UI", sop)
           + w.element(0x0008, 0x0060, "CS", modality)
           + w.element(0x0008, 0x103E, "LO", "fuzz seed")
           + w.element(0x0010, 0x0010, "PN", "Seed^Synthetic")
           + w.element(0x0018, 0x0050, "DS", "1.5"))
    out += w.element(0x0020, 0x000D, "UI", STUDY) + w.element(0x0020, 0x000E, "UI", SERIES)
    out += w.element(0x0020, 0x0011, "IS", "3") + w.element(0x0020, 0x0013, "IS", "1")
    if geometry:
        out += w.element(0x0020, 0x0032, "DS", "-10\\-20.5\\30")
        out += w.element(0x0020, 0x0037, "DS", "1\\0\\0\\0\\1\\0")
    out += w.us(0x0028, 0x0002, 1) + w.element(0x0028, 0x0004, "CS", "MONOCHROME2")
    if frames is not None:
        out += w.element(0x0028, 0x0008, "IS", str(frames))
    out += w.us(0x0028, 0x0010, rows) + w.us(0x0028, 0x0011, cols)
    if geometry:
        out += w.element(0x0028, 0x0030, "DS", "0.5\\0.75")
    out += w.us(0x0028, 0x0100, bits) + w.us(0x0028, 0x0101, 12 if bits == 16 else bits)
    out += w.us(0x0028, 0x0102, 11 if bits == 16 else bits - 1) + w.us(0x0028, 0x0103, 0)
    out += w.element(0x0028, 0x1052, "DS", "-1024") + w.element(0x0028, 0x1053, "DS", "1")
    return out


def pixels(w, count, bits=16):
    fmt = {8: "B", 16: "H", 32: "I"}[bits]
    data = struct.pack(w.e + fmt * count, *[(i * 37) % 4000 for i in range(count)])
    return w.element(0x7FE0, 0x0010, "OW" if bits != 8 else "OB", data)


def ct(syntax=EXPLICIT_LE, preamble=True, sop="1.2.826.0.1.3680043.9.7433.3.1"):
    w = Writer(explicit=syntax != IMPLICIT_LE, big=syntax == EXPLICIT_BE)
    body = image_header(w, CT_CLASS, sop) + pixels(w, 64)
    return (meta(syntax, CT_CLASS, sop) if preamble else b"") + body


def enhanced_mr(frames=2):
    cls, sop = "1.2.840.10008.5.1.4.1.1.4.1", "1.2.826.0.1.3680043.9.7433.3.2"
    w = Writer()
    shared = w.sequence(0x5200, 0x9229, [
        w.sequence(0x0028, 0x9110, [w.element(0x0028, 0x0030, "DS", "0.9\\0.9")
                                    + w.element(0x0018, 0x0050, "DS", "2")], undefined=False)
        + w.sequence(0x0020, 0x9116, [w.element(0x0020, 0x0037, "DS", "1\\0\\0\\0\\1\\0")])
        + w.sequence(0x0028, 0x9145, [w.element(0x0028, 0x1052, "DS", "0")
                                      + w.element(0x0028, 0x1053, "DS", "2")])])
    per_frame = w.sequence(0x5200, 0x9230, [
        w.sequence(0x0020, 0x9113, [w.element(0x0020, 0x0032, "DS", f"0\\0\\{2 * f}")])
        + w.sequence(0x0018, 0x9226, [w.element(0x0008, 0x9007, "CS", "ORIGINAL\\PRIMARY\\M\\NONE")])
        for f in range(frames)])
    body = image_header(w, cls, sop, modality="MR", frames=frames, geometry=False)
    return meta(EXPLICIT_LE, cls, sop) + body + shared + per_frame + pixels(w, 64 * frames)


def legacy_multiframe(frames=3):
    sop = "1.2.826.0.1.3680043.9.7433.3.3"
    w = Writer()
    body = image_header(w, CT_CLASS, sop, frames=frames) + w.element(0x0018, 0x0088, "DS", "2.5")
    return meta(EXPLICIT_LE, CT_CLASS, sop) + body + pixels(w, 64 * frames)


def rt_dose(frames=3, offsets="0\\2"):
    """An RT dose grid whose GridFrameOffsetVector is shorter than its frames."""
    cls, sop = "1.2.840.10008.5.1.4.1.1.481.2", "1.2.826.0.1.3680043.9.7433.3.4"
    w = Writer()
    body = image_header(w, cls, sop, modality="RTDOSE", frames=frames, bits=32)
    body += w.element(0x0028, 0x0009, "AT", struct.pack("<HH", 0x3004, 0x000C))
    body += w.element(0x3004, 0x0002, "CS", "GY") + w.element(0x3004, 0x000C, "DS", offsets)
    body += w.element(0x3004, 0x000E, "DS", "0.0001")
    return meta(EXPLICIT_LE, cls, sop) + body + pixels(w, 64 * frames, bits=32)


def dicomdir():
    cls, sop = "1.2.840.10008.1.3.10", "1.2.826.0.1.3680043.9.7433.3.5"
    w = Writer()
    record = (w.element(0x0004, 0x1430, "CS", "IMAGE") + w.element(0x0004, 0x1500, "CS", "IMG\\SEED1")
              + w.element(0x0004, 0x1510, "UI", CT_CLASS))
    body = (w.element(0x0004, 0x1130, "CS", "SEED") + w.sequence(0x0004, 0x1220, [record])
            + w.element(0x0008, 0x0016, "UI", cls))
    return meta(EXPLICIT_LE, cls, sop) + body


def rle_segment(data):
    """PackBits as DICOM RLE wants it: literal runs of at most 128 bytes."""
    out = b""
    for i in range(0, len(data), 128):
        chunk = data[i:i + 128]
        out += bytes([len(chunk) - 1]) + chunk
    return out + (b"\0" if len(out) % 2 else b"")


def rle_ct():
    sop = "1.2.826.0.1.3680043.9.7433.3.6"
    w = Writer()
    values = [(i * 37) % 4000 for i in range(64)]
    high = rle_segment(bytes(v >> 8 for v in values))
    low = rle_segment(bytes(v & 0xFF for v in values))
    header = struct.pack("<16I", 2, 64, 64 + len(high), *([0] * 13))
    frame = header + high + low
    fragments = (struct.pack("<HHI", 0xFFFE, 0xE000, 0)
                 + struct.pack("<HHI", 0xFFFE, 0xE000, len(frame)) + frame
                 + struct.pack("<HHI", 0xFFFE, 0xE0DD, 0))
    pixel = struct.pack("<HH", 0x7FE0, 0x0010) + b"OB\0\0" + struct.pack("<I", UNDEFINED) + fragments
    return meta(RLE, CT_CLASS, sop) + image_header(w, CT_CLASS, sop) + pixel


def dicom_seeds(out):
    seeds = {
        "ct_explicit_le.dcm": ct(),
        "ct_implicit_le.dcm": ct(IMPLICIT_LE),
        "ct_explicit_be.dcm": ct(EXPLICIT_BE),
        "ct_bare_implicit.dcm": ct(IMPLICIT_LE, preamble=False)[0:],
        "mr_enhanced.dcm": enhanced_mr(),
        "ct_legacy_multiframe.dcm": legacy_multiframe(),
        "rtdose_short_offsets.dcm": rt_dose(),
        "dicomdir.dcm": dicomdir(),
        "ct_rle.dcm": rle_ct(),
        # zero padding after the data set (CD/DVD media): read, with a warning
        "ct_trailing_zeros.dcm": ct() + bytes(200),
        "ct_implicit_trailing_zeros.dcm": ct(IMPLICIT_LE) + bytes(13),
    }
    for name, data in seeds.items():
        (out / name).write_bytes(data)
    # Compressed variants of the explicit CT, made by the codecs' own tools.
    tools = {
        "ct_jpeg_lossless.dcm": ["dcmcjpeg", "+el"],
        "ct_jpeg_sv1.dcm": ["dcmcjpeg", "+e1"],
        "ct_jpegls_lossless.dcm": ["dcmcjpls", "+el"],
        "ct_jpegls_near.dcm": ["dcmcjpls", "+en", "+md", "2", "+un"],  # +un: the same UID every run
        "ct_deflated.dcm": ["dcmconv", "+td"],
        "ct_j2k.dcm": ["gdcmconv", "--j2k"],
    }
    for name, cmd in tools.items():
        if shutil.which(cmd[0]) is None:
            print(f"make_seeds: {cmd[0]} not found, {name} not made", file=sys.stderr)
            continue
        subprocess.run(cmd + [str(out / "ct_explicit_le.dcm"), str(out / name)], check=True)


def protocol_seeds(out):
    text = (ROOT / "docs" / "protocol.md").read_text()
    messages = sorted({m for m in re.findall(r'\{"type":.*\}', text)})
    for n, message in enumerate(messages):
        try:
            json.loads(message)
        except json.JSONDecodeError:
            continue
        (out / f"message_{n:03}.json").write_text(message)
    header = json.dumps({"width": 4, "height": 2, "format": "png", "seq": 7, "quality": "still",
                         "render_ms": 1.5, "encode_ms": 0.5, "scale": 1, "jpeg_quality": 0},
                        separators=(",", ":")).encode()
    (out / "frame_png.bin").write_bytes(struct.pack(">I", len(header)) + header + b"\x89PNG\r\n")
    keys = sorted(set(re.findall(r'"([a-z_\-]+)":', text)) | set(re.findall(r'"type":"([a-z\-]+)"', text)))
    (FUZZ / "dict" / "protocol.dict").write_text(
        "# JSON keys and message types of docs/protocol.md (made by fuzz/seeds/make_seeds.py)\n"
        + "".join(f'"\\"{k}\\""\n' for k in keys)
        + '"{"\n"}"\n"["\n"]"\n":"\n","\n"true"\n"false"\n"null"\n"1e308"\n"-0"\n')


def recording_seeds(out):
    # A recording as lucent-server writes it (protocol/Recording.h): header, start, messages.
    def line(obj):
        return json.dumps(obj, separators=(",", ":"), sort_keys=True) + "\n"
    header = {"lucent_recording": 1, "series": "1.2.826.0.1.3680043.9.7433.3.1", "width": 64,
              "height": 48, "created": 1790000000000, "duration_ms": 900, "views": 4}
    start = [{"type": "size", "width": 64, "height": 48}, {"type": "tf", "preset": "ct-bone"},
             {"type": "mode", "mode": "dvr"}, {"type": "clip"},
             {"type": "camera", "azimuth": 0.0, "elevation": 0.0, "zoom": 1.0},
             {"type": "sampling", "step": 0.5, "interp": "linear"}]
    messages = [(100, {"type": "interaction", "state": "start"}),
                (120, {"type": "camera", "azimuth": 30.0}),
                (300, {"type": "interaction", "state": "end"}),
                (500, {"type": "tf", "preset": "ct-soft-tissue"}),
                (900, {"type": "mode", "mode": "iso", "iso": 300.0})]
    text = line(header) + "".join(line({"start": m}) for m in start)
    text += "".join(line({"at_ms": t, "message": m}) for t, m in messages)
    (out / "session.jsonl").write_text(text)
    header["views"] = 1
    header["duration_ms"] = 0
    (out / "start_only.jsonl").write_text(line(header) + "".join(line({"start": m}) for m in start))


def http_seeds(out):
    heads = {
        "get_root.http": "GET / HTTP/1.1\r\nHost: localhost:8080\r\nAccept: text/html\r\n\r\n",
        "get_app.http": "GET /app.js?v=1 HTTP/1.0\r\nHost: x\r\n\r\n",
        "upgrade.http": ("GET /ws HTTP/1.1\r\nHost: localhost\r\nUpgrade: websocket\r\n"
                         "Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                         "Sec-WebSocket-Protocol: lucent.v2, lucent.v1\r\n"
                         "Sec-WebSocket-Version: 13\r\n\r\n"),
        "post_upload.http": ("POST /studies HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer abc123\r\n"
                             "Content-Type: multipart/related; type=\"application/dicom\"; boundary=b1\r\n"
                             "Content-Length: 1234\r\nExpect: 100-continue\r\n\r\n"),
        "chunked.http": "POST /studies/ HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n",
    }
    for name, text in heads.items():
        (out / name).write_bytes(text.encode())


def upload_seeds(out):
    part = ct()
    multipart = (b"--b1\r\nContent-Type: application/dicom\r\n\r\n" + part
                 + b"\r\n--b1\r\nContent-Type: application/dicom\r\n\r\n" + part + b"\r\n--b1--\r\n")
    seeds = {
        "multipart_two.txt": b'multipart/related; type="application/dicom"; boundary=b1\n' + multipart,
        "multipart_preamble.txt": (b"Multipart/Related; boundary=\"b1\"\npreamble\r\n" + multipart),
        "single.txt": b"application/dicom\n" + part,
    }
    for name, data in seeds.items():
        (out / name).write_bytes(data)


def multipart_seeds(out):
    """WADO-RS answers for fuzz_multipart: Content-Type line, one byte seeding the chunking, body."""
    part = b"DICM" + bytes(range(16)) + b"\r\n--not-the-boundary\r\n"
    two = (b"preamble\r\n--b1\r\nContent-Type: application/dicom\r\n\r\n" + part
           + b"\r\n--b1\r\nContent-Type: application/dicom\r\nContent-Length: 24\r\n\r\n" + part
           + b"\r\n--b1--\r\nepilogue")
    seeds = {
        "two_parts.txt": b'multipart/related; type="application/dicom"; boundary=b1\n\x07' + two,
        "quoted_no_headers.txt": (b'Multipart/Related; boundary="a b"; type=application/dicom\n\x2a'
                                  b"--a b\r\n\r\n" + part + b"\r\n--a b  \r\n\r\nx\r\n--a b--"),
        "cut_short.txt": b"multipart/related; boundary=b1\n\x01--b1\r\n\r\nhalf a part\r\n--b",
        "empty_part.txt": b"multipart/related; boundary=xyz\n\xff--xyz\r\n\r\n\r\n--xyz--\r\n",
    }
    for name, data in seeds.items():
        (out / name).write_bytes(data)


def metaimage_seeds(out):
    voxels = struct.pack("<8h", *range(-4, 4))
    base = ("ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementSpacing = 0.5 0.5 1\n"
            "Offset = -1 2 3.5\nTransformMatrix = 1 0 0 0 1 0 0 0 1\nModality = MET_MOD_CT\n")
    (out / "short_local.mha").write_bytes(
        (base + "ElementType = MET_SHORT\nElementDataFile = LOCAL\n").encode() + voxels)
    (out / "uchar_msb.mha").write_bytes(
        (base + "BinaryDataByteOrderMSB = True\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n")
        .encode() + bytes(range(8)))
    packed = zlib.compress(struct.pack("<8f", *[i * 0.5 for i in range(8)]))
    (out / "float_zlib.mha").write_bytes(
        (base + f"CompressedData = True\nCompressedDataSize = {len(packed)}\n"
                "ElementType = MET_FLOAT\nElementDataFile = LOCAL\n").encode() + packed)


def nifti_header(dims, datatype, bitpix, sform=True):
    h = bytearray(352)
    struct.pack_into("<i", h, 0, 348)
    struct.pack_into("<8h", h, 40, len(dims), *dims, *([1] * (7 - len(dims))))
    struct.pack_into("<hh", h, 70, datatype, bitpix)
    struct.pack_into("<8f", h, 76, 1.0, 0.5, 0.5, 2.0, 1.0, 1.0, 1.0, 1.0)
    struct.pack_into("<f", h, 108, 352.0)
    struct.pack_into("<ff", h, 112, 1.0, 0.0)  # scl_slope, scl_inter
    struct.pack_into("<hh", h, 252, 1, 1 if sform else 0)  # qform_code, sform_code
    struct.pack_into("<6f", h, 256, 0.0, 0.0, 0.0, 10.0, -5.0, 2.5)  # quatern b c d, qoffset
    if sform:
        struct.pack_into("<12f", h, 280, -0.5, 0, 0, 10, 0, -0.5, 0, -5, 0, 0, 2, 2.5)
    h[344:348] = b"n+1\0"
    return bytes(h)


def nifti_seeds(out):
    (out / "int16_sform.nii").write_bytes(nifti_header([2, 2, 2], 4, 16) + struct.pack("<8h", *range(8)))
    (out / "float_qform_4d.nii").write_bytes(
        nifti_header([2, 2, 1, 2], 16, 32, sform=False) + struct.pack("<8f", *range(8)))
    big = bytearray(nifti_header([2, 2, 2], 512, 16))
    for offset, fmt in ((0, "i"), (40, "8h"), (70, "hh"), (76, "8f"), (108, "f"), (112, "ff"),
                        (252, "hh"), (256, "6f"), (280, "12f")):
        values = struct.unpack_from("<" + fmt, big, offset)
        struct.pack_into(">" + fmt, big, offset, *values)
    (out / "uint16_big_endian.nii").write_bytes(bytes(big) + struct.pack(">8H", *range(8)))


INV3_PLIST = """<?xml version="1.0" encoding="UTF-8"?>
<!DOCTYPE plist PUBLIC "-//Apple//DTD PLIST 1.0//EN" "http://www.apple.com/DTDs/PropertyList-1.0.dtd">
<plist version="1.0">
<dict>
\t<key>name</key>
\t<string>seed</string>
\t<key>modality</key>
\t<string>CT</string>
\t<key>spacing</key>
\t<array><real>0.5</real><real>0.5</real><real>1.5</real></array>
\t<key>matrix</key>
\t<dict>
\t\t<key>dtype</key>
\t\t<string>int16</string>
\t\t<key>filename</key>
\t\t<string>matrix.dat</string>
\t\t<key>shape</key>
\t\t<array><integer>2</integer><integer>2</integer><integer>2</integer></array>
\t</dict>
</dict>
</plist>
"""


def plist_seeds(out):
    """main.plist files for fuzz_plist: the project's, and one with every value type."""
    (out / "main.plist").write_bytes(INV3_PLIST.encode())
    every = """<?xml version="1.0" encoding="UTF-8"?>
<plist version="1.0">
<dict>
\t<key>string</key><string>a &amp; b &lt;c&gt; &#x41;&#66;</string>
\t<key>integer</key><integer>-42</integer>
\t<key>real</key><real>-1.5e3</real>
\t<key>true</key><true/>
\t<key>false</key><false/>
\t<key>date</key><date>2012-09-14T15:12:08Z</date>
\t<key>data</key><data>aGVsbG8gd29ybGQ=</data>
\t<key>empty</key><dict/>
\t<key>nested</key><array><array><dict><key>k</key><string/></dict></array></array>
\t<!-- a comment -->
</dict>
</plist>
"""
    (out / "every_type.plist").write_bytes(every.encode())


def inv3_seed(out):
    plist = INV3_PLIST
    members = {"seed/main.plist": plist.encode(), "seed/matrix.dat": struct.pack("<8h", *range(8))}
    buffer = io.BytesIO()
    with tarfile.open(fileobj=buffer, mode="w", format=tarfile.USTAR_FORMAT) as tar:
        for name, data in members.items():
            info = tarfile.TarInfo(name)
            info.size, info.mtime, info.mode = len(data), 0, 0o644
            info.uname = info.gname = ""
            tar.addfile(info, io.BytesIO(data))
    # Plain tar: the fuzzer mutates what the reader sees (libarchive reads it as it is);
    # gzipped (mtime 0: the same bytes every time) for libarchive's gzip filter.
    (out / "project.tar.inv3").write_bytes(buffer.getvalue())
    (out / "project.tar.gz.inv3").write_bytes(gzip.compress(buffer.getvalue(), mtime=0))


def main():
    makers = {"dicom": dicom_seeds, "protocol": protocol_seeds, "http_head": http_seeds,
              "upload_parts": upload_seeds, "metaimage": metaimage_seeds, "nifti": nifti_seeds,
              "inv3": inv3_seed, "recording": recording_seeds, "multipart": multipart_seeds,
              "plist": plist_seeds}
    # make_seeds.py [--out DIR] [NAME ...]: the DICOM seeds are not committed (the
    # repository holds no DICOM files); fuzz.sh and the regression tests make them.
    args = sys.argv[1:]
    root = CORPUS
    if args[:1] == ["--out"]:
        root = pathlib.Path(args[1])
        args = args[2:]
    (FUZZ / "dict").mkdir(exist_ok=True)
    for name, make in makers.items():
        if args and name not in args:
            continue
        out = root / name
        shutil.rmtree(out, ignore_errors=True)
        out.mkdir(parents=True)
        make(out)


if __name__ == "__main__":
    main()
