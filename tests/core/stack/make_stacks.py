#!/usr/bin/env python3
"""Makes the 2D image stacks of test_image_stack in OUT_DIR from real CT slices of
DATA_DIR (../shared/data), with DCMTK and GDCM only: dcmj2pnm windows a CT slice
to an 8-bit PGM; this script colours it (a fixed map, written as PPM and BMP: image
files, not DICOM); img2dcm makes an RGB Secondary Capture of it in the CT's study;
dcmcjpeg, dcmdjpeg, dcmcrle, dcmcjpls, gdcmconv and dcmquant re-encode that (JPEG
baseline YBR_FULL_422, uncompressed YBR_FULL, RLE, JPEG lossless, JPEG-LS, JPEG 2000,
palette colour);
gdcmimg makes multi-frame cine objects from several coloured (or grey) slices;
dcmodify sets what the tools leave out (frame time, MONOCHROME1). Each case is one
folder with one file and its own series UID. Sources of the expected pixels:
ct.ppm (the coloured slice), cine_rgb.raw / cine_grey.raw (the frames, raw), palette.ppm
(DCMTK's own rendering of the palette file).
Usage: make_stacks.py OUT_DIR DATA_DIR"""
import pathlib
import shutil
import struct
import subprocess
import sys

SERIES = "dcm_qa_ct/Philips_S21570/S2010"  # 28 real CT slices 512x512
SLICE = SERIES + "/I100"
CINE = ["I10", "I20", "I30", "I40", "I50", "I60"]
WINDOW = ["+Ww", "40", "400"]


def run(*args):
    subprocess.run([str(a) for a in args], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)


def read_pgm(path):
    data = path.read_bytes()
    fields, at = [], 0
    while len(fields) < 4:
        while data[at:at + 1].isspace():
            at += 1
        end = at
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[at:end])
        at = end
    width, height = int(fields[1]), int(fields[2])
    return width, height, data[at + 1:at + 1 + width * height]


def colour(v):
    """A smooth map with three different channels (so a swapped channel shows)."""
    return v, v * v // 255, 255 - v // 2


def coloured(grey):
    out = bytearray()
    for v in grey:
        out += bytes(colour(v))
    return bytes(out)


def write_bmp(path, width, height, rgb):
    """24-bit BMP (what img2dcm reads besides JPEG): bottom-up BGR rows."""
    stride = (3 * width + 3) & ~3
    pixels = bytearray()
    for y in range(height - 1, -1, -1):
        row = rgb[3 * y * width:3 * (y + 1) * width]
        line = bytearray(3 * width)
        line[0::3], line[1::3], line[2::3] = row[2::3], row[1::3], row[0::3]
        pixels += line + b"\0" * (stride - 3 * width)
    header = struct.pack("<2sIHHI", b"BM", 54 + len(pixels), 0, 0, 54)
    info = struct.pack("<IiiHHIIiiII", 40, width, height, 1, 24, 0, len(pixels), 2835, 2835, 0, 0)
    path.write_bytes(header + info + bytes(pixels))


def windowed(data, name, out):
    pgm = out / (name + ".pgm")
    run("dcmj2pnm", *WINDOW, "+op", data / SERIES / name, pgm)
    return read_pgm(pgm)


def case(out, name, make):
    """One case folder holding case.dcm with a new series (and instance) UID."""
    folder = out / name
    folder.mkdir(parents=True, exist_ok=True)
    target = folder / "case.dcm"
    make(target)
    run("dcmodify", "-nb", "-gse", "-gin", "-i", f"SeriesDescription={name}", target)
    return target


def main():
    out, data = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    if out.exists():
        shutil.rmtree(out)
    work = out / "work"
    work.mkdir(parents=True)
    ct = data / SLICE
    if not ct.exists():  # no ../shared/data: the test skips, naming what is missing
        shutil.rmtree(work)
        (out / "stamp").write_text(f"missing {ct}\n")
        return

    width, height, grey = windowed(data, "I100", work)
    rgb = coloured(grey)
    (out / "ct.ppm").write_bytes(b"P6\n%d %d\n255\n" % (width, height) + rgb)
    write_bmp(work / "ct.bmp", width, height, rgb)
    source = work / "rgb.dcm"
    run("img2dcm", "-i", "BMP", "--study-from", ct, "-k", "Modality=OT", work / "ct.bmp", source)

    case(out, "rgb", lambda t: shutil.copyfile(source, t))
    case(out, "jpeg_baseline_ybr422", lambda t: run("dcmcjpeg", "+eb", source, t))
    case(out, "ybr_full",
         lambda t: run("dcmdjpeg", "+cn", out / "jpeg_baseline_ybr422" / "case.dcm", t))
    case(out, "rle", lambda t: run("dcmcrle", source, t))
    case(out, "jpeg_lossless", lambda t: run("dcmcjpeg", "+e1", source, t))
    case(out, "j2k_lossless", lambda t: run("gdcmconv", "--j2k", source, t))
    case(out, "jpegls_lossless", lambda t: run("dcmcjpls", source, t))
    palette = case(out, "palette", lambda t: run("dcmquant", source, t))
    run("dcm2pnm", "+op", palette, out / "palette.ppm")

    def monochrome1(target):
        shutil.copyfile(ct, target)
        target.chmod(0o644)
        run("dcmodify", "-nb", "-m", "PhotometricInterpretation=MONOCHROME1", target)
    case(out, "monochrome1", monochrome1)

    # Cine: six slices of the series as frames of one object.
    frames = [windowed(data, name, work)[2] for name in CINE]
    (out / "cine_rgb.raw").write_bytes(b"".join(coloured(f) for f in frames))
    (out / "cine_grey.raw").write_bytes(b"".join(frames))
    size = f"{width},{height},{len(CINE)}"

    def us_cine(target):
        run("gdcmimg", "-i", out / "cine_rgb.raw", "-o", target, "--size", size, "--spp", "3",
            "--depth", "8", "-C", "1.2.840.10008.5.1.4.1.1.3.1")
        run("dcmodify", "-nb", "-i", "Modality=US", "-i", "FrameTime=40",
            "-i", "(0028,0009)=(0018,1063)", target)
    us = case(out, "us_cine", us_cine)
    case(out, "us_cine_jpeg", lambda t: run("dcmcjpeg", "+eb", us, t))

    def xa_cine(target):
        run("gdcmimg", "-i", out / "cine_grey.raw", "-o", target, "--size", size, "--spp", "1",
            "--depth", "8", "-C", "1.2.840.10008.5.1.4.1.1.12.1")
        run("dcmodify", "-nb", "-i", "Modality=XA", "-i", "FrameTimeVector=0\\50\\50\\100\\100\\100",
            "-i", "(0028,0009)=(0018,1065)", "-i", "WindowCenter=128", "-i", "WindowWidth=200",
            target)
    case(out, "xa_cine", xa_cine)
    shutil.rmtree(work)
    (out / "stamp").write_text("made\n")


if __name__ == "__main__":
    main()
