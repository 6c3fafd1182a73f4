// Inputs that fuzz_dicom (fuzz/DicomFuzzer.cpp) found, each once a runaway
// allocation, an assertion or a leak inside GDCM (fuzz-regressions/README.md says which), fed
// through the same scan and load as any file: each must end in a reason that
// names the file or the element and what is wrong.
#include <QTest>

#include <filesystem>
#include <string>

#include "core/io/Catalog.h"
#include "tests/support/RealData.h"

namespace fs = std::filesystem;
using namespace lucent;

namespace {

fs::path regressionInput(const char* name) {
    return fs::path(LUCENT_FUZZ_INPUTS_DIR) / name; // made by fuzz-regressions/make_inputs.py
}

// The reason the scan gives for skipping the file; it must yield no series.
QString skipReason(const fs::path& file) {
    const Catalog catalog = scanPath(file);
    if (!catalog.series.empty() || catalog.skipped.size() != 1) {
        return "(not skipped as one file)";
    }
    return QString::fromStdString(catalog.skipped.front().reason);
}

// The LoadError of loading the one series the file holds; it must name the file.
QString loadError(const fs::path& file) {
    const Catalog catalog = scanPath(file);
    if (catalog.series.size() != 1) {
        return "(not one series)";
    }
    try {
        (void)loadSeries(catalog.series.front());
    } catch (const LoadError& e) {
        const QString what = e.what();
        return what.contains(QString::fromStdString(file.string())) ? what
                                                                    : "(file not named) " + what;
    }
    return "(loaded without an error)";
}

} // namespace

class TestDicomFuzzRegressions : public QObject {
    Q_OBJECT

private slots:
    void unknownVrIsRefusedBeforeGdcmAllocatesItsLength() {
        const QString reason = skipReason(regressionInput("unknown-vr-huge-length.dcm"));
        QVERIFY2(reason.contains("corrupt DICOM file"), qPrintable(reason));
        QVERIFY2(reason.contains("unknown value representation 'FS'"), qPrintable(reason));
        QVERIFY2(reason.contains("(0020,0037)"), qPrintable(reason));
    }

    void delimiterWithALengthIsRefusedBeforeGdcmAllocatesIt() {
        // An RLE file whose pixel data's sequence delimiter declares 0xBD000000 bytes.
        const QString reason = skipReason(regressionInput("delimiter-with-a-length.dcm"));
        QVERIFY2(reason.contains("corrupt DICOM file"), qPrintable(reason));
        QVERIFY2(reason.contains("sequence delimiter with a length of 3170893824 (must be 0)"),
                 qPrintable(reason));
    }
    void elementInsideAnItemIsWalkedToo() {
        const QString reason = skipReason(regressionInput("nested-element-huge-length.dcm"));
        QVERIFY2(reason.contains("corrupt DICOM file"), qPrintable(reason));
        QVERIFY2(reason.contains("runs past the end of its item"), qPrintable(reason));
    }

    void pixelDataOfAnotherVrIsRefusedBeforeGdcmAsserts() {
        const QString reason = skipReason(regressionInput("pixel-data-of-vr-sq-big-endian.dcm"));
        QVERIFY2(reason.contains("corrupt DICOM file: Pixel Data (7FE0,0010) has VR 'SQ', not OB "
                                 "or OW"),
                 qPrintable(reason));
    }

    void undefinedLengthOfAnOdElementIsRefusedBeforeGdcmAsserts() {
        const QString reason = skipReason(regressionInput("undefined-length-of-vr-od.dcm"));
        QVERIFY2(reason.contains("corrupt DICOM file"), qPrintable(reason));
        QVERIFY2(reason.contains("element (0020,9113) of VR 'OD' has an undefined length"),
                 qPrintable(reason));
    }

    void metaInformationSequenceIsRefusedBeforeGdcmAsserts() {
        const QString reason = skipReason(regressionInput("meta-element-of-vr-sq.dcm"));
        QVERIFY2(reason.contains("corrupt DICOM file: file meta information element (0002,0001) "
                                 "is a sequence"),
                 qPrintable(reason));
    }

    void corruptDeflatedDataSetIsRefused() {
        const QString reason = skipReason(regressionInput("deflated-corrupt.dcm"));
        QVERIFY2(reason.contains("corrupt DICOM file: deflated data set"), qPrintable(reason));
    }

    void jpegFrameWithoutEndOfImageIsALoadError() {
        const QString what = loadError(regressionInput("jpeg-without-end-of-image.dcm"));
        QVERIFY2(what.contains("JPEG pixel data (7FE0,0010): cut short"), qPrintable(what));
    }

    void jpegLsFrameWithoutScanIsALoadError() {
        const QString what = loadError(regressionInput("jpegls-without-scan.dcm"));
        QVERIFY2(what.contains("dcmdjpls could not decode the JPEG-LS data"), qPrintable(what));
    }

    void rleHeaderOutOfRangeIsALoadError() {
        const QString what = loadError(regressionInput("rle-segment-count-out-of-range.dcm"));
        QVERIFY2(what.contains("RLE pixel data (7FE0,0010): frame 1: the RLE header declares "
                               "16775682 segment(s), BitsAllocated 16 needs 2"),
                 qPrintable(what));
    }

    void jpegFrameOfAnotherSizeIsALoadError() {
        const QString what = loadError(regressionInput("jpeg-size-not-the-image.dcm"));
        QVERIFY2(what.contains("JPEG pixel data (7FE0,0010): frame 1: the JPEG frame is "
                               "49416x8 with 1 component(s), the header says 8x8"),
                 qPrintable(what));
    }

    void highBitAboveBitsStoredIsALoadErrorBeforeGdcmAsserts() {
        const QString what =
            loadError(regressionInput("high-bit-above-bits-stored-big-endian.dcm"));
        QVERIFY2(what.contains("HighBit (0028,0102) 11 is not BitsStored (0028,0101) 8 - 1"),
                 qPrintable(what));
    }

    void orientationWithAZeroDirectionIsRefused() {
        const QString reason = skipReason(regressionInput("orientation-with-a-zero-column.dcm"));
        QVERIFY2(reason.contains("frame 1: ImageOrientationPatient (0020,0037): its row and column "
                                 "directions are no unit vectors (lengths 1.414 and 0)"),
                 qPrintable(reason));
    }

    void itemTagAmongTheElementsIsRefusedBeforeGdcmAsserts() {
        const QString reason = skipReason(regressionInput("item-tag-among-the-elements.dcm"));
        QVERIFY2(reason.contains("(FFFE,600D) among the elements, outside a sequence"),
                 qPrintable(reason));
    }

    // JPEG 2000 is decoded in lucent-frame-decoder: GDCM's codec crashed on this one
    // (SEGV in JPEG2000Codec::DecodeByStreamsCommon; lucent-cli convert died with 139).
    // The decoder dies instead, and the next file gets a new one.
    void j2kCodestreamThatCrashesTheCodecIsALoadError() {
        REQUIRE_DATA("nema_wg04/CT1/CT1_J2KR.dcm");
        const QString what = loadError(regressionInput("j2k-codestream-crashes-the-codec.dcm"));
#ifdef __SANITIZE_ADDRESS__
        // AddressSanitizer's allocator places the codec's buffer where the write past it
        // lands in mapped memory: the decoder may then answer with what it wrote. This
        // process stays whole either way, which is what the decoder process is for.
        QVERIFY2(what.contains("the frame decoder stopped by signal") ||
                     what == "(loaded without an error)",
                 qPrintable(what));
#else
        QVERIFY2(what.contains("the frame decoder stopped by signal"), qPrintable(what));
#endif
        const Catalog good = scanPath(test::kRealData / "nema_wg04/CT1/CT1_J2KR.dcm");
        QCOMPARE(good.series.size(), std::size_t(1));
        const Volume v = loadSeries(good.series.front());
        QCOMPARE(v.geometry().dims, glm::ivec3(512, 512, 1));
    }

    // ... and leaked what OpenJPEG allocated (112 bytes a load) on this one.
    void j2kCodestreamThatLeaksInTheCodecIsALoadError() {
        REQUIRE_DATA("nema_wg04/CT1/CT1_J2KI.dcm");
        const QString what = loadError(regressionInput("j2k-codestream-leaks-in-the-codec.dcm"));
        QVERIFY2(what.contains("pixel data could not be decoded (1.2.840.10008.1.2.4.91)"),
                 qPrintable(what));
    }

    // ... and allocated gigabytes for half a minute before crashing: the decoder's
    // requests may map only what they can need, so it fails at once.
    void j2kCodestreamThatAllocatesGigabytesIsALoadError() {
        REQUIRE_DATA("nema_wg04/CT1/CT1_J2KI.dcm");
        const QString what = loadError(regressionInput("j2k-codestream-allocates-gigabytes.dcm"));
#ifdef __SANITIZE_ADDRESS__
        // Under AddressSanitizer the decoder's limit is the sanitizer's, which ends it.
        QVERIFY2(what.contains("pixel data could not be decoded (1.2.840.10008.1.2.4.91)") ||
                     what.contains("the frame decoder exited with status 1"),
                 qPrintable(what));
#else
        QVERIFY2(what.contains("pixel data could not be decoded (1.2.840.10008.1.2.4.91)"),
                 qPrintable(what));
#endif
    }

    // The walk takes zero bytes after the last element as padding; GDCM's reader
    // asserted on 7 of them where no Pixel Data ended its read first. GDCM now
    // reads the file only up to the padding (DataSetStream).
    void zeroPaddingNeverReachesGdcm() {
        const QString reason =
            skipReason(regressionInput("seven-zero-bytes-without-pixel-data.dcm"));
        QVERIFY2(reason == "no pixel data (7FE0,0010 missing)", qPrintable(reason));
    }

    // File meta elements repeated after a group length that ends among them:
    // GDCM read another transfer syntax than the walk, guessed at the encoding
    // and allocated 2.4 GB. Refused by the walk.
    void repeatedMetaElementsAreRefused() {
        REQUIRE_DATA("dcmqi_ct3slice/01.dcm");
        const QString reason = skipReason(regressionInput("meta-elements-repeated.dcm"));
        QVERIFY2(reason.contains("file meta information element (0002,0002) repeated or out of "
                                 "order, at byte 324"),
                 qPrintable(reason));
    }

    // (7FE0,0010) with VR SQ inside an Enhanced MR's functional group item:
    // GDCM asserted (`TagField != Tag(0x7fe0,0x0010)`) and aborted the scan.
    // Found by fuzz_dicom on the code before issue 27 too.
    void pixelDataOfVrSqInsideAnItemIsRefused() {
        const QString reason =
            skipReason(regressionInput("pixel-data-sequence-inside-an-item.dcm"));
        QVERIFY2(reason.contains("Pixel Data (7FE0,0010) has VR 'SQ', not OB or OW"),
                 qPrintable(reason));
    }

    // An implicit VR data set under a meta header that says explicit: GDCM's
    // own guess at the encoding read a length of about 4 GB and allocated it.
    // GDCM now reads the file with a meta header that says implicit.
    void implicitDataUnderAnExplicitMetaIsReadAsImplicit() {
        REQUIRE_DATA("dcmqi_ct3slice/01.dcm");
        const QString reason =
            skipReason(regressionInput("implicit-under-explicit-meta-misread.dcm"));
        QVERIFY2(reason == "inconsistent BitsStored 0 / HighBit 15 for BitsAllocated 16",
                 qPrintable(reason));
    }

    // A meta group length past the group's last element, over zero bytes: GDCM
    // read them as meta elements and asserted. Refused by the walk.
    void metaGroupLengthOverBytesThatAreNoElementIsRefused() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S1000/I10");
        const QString reason = skipReason(regressionInput("meta-group-length-past-zeros.dcm"));
        QVERIFY2(reason.contains("file meta information group length (0002,0000) says the group "
                                 "ends at byte 350, past its last element at byte 314"),
                 qPrintable(reason));
    }
};

QTEST_APPLESS_MAIN(TestDicomFuzzRegressions)
#include "test_dicom_fuzz_regressions.moc"
