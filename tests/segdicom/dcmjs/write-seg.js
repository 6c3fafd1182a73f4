// A DICOM SEG written by dcmjs (OHIF's DICOM library) the way OHIF writes one: the CT slices
// normalized into a multi-frame dataset, a dcmjs Segmentation derived from it, and each
// segment filled from a labelmap by the Cornerstone adapter's fillSegmentation. Lucent's tests
// use it as a foreign writer (tests/segdicom/DcmjsWriter.h writes the job).
//
// node write-seg.js JOB.json: JOB names the CT files, the SOP Instance UID of each slice k of
// the grid, and per segment its description and a file of its bits (bit k*rows*columns +
// row*columns + column). Prints {"parseMs":..,"writeMs":..}: the CT parsed, and what dcmjs
// itself took.
"use strict";
const fs = require("fs");
const dcmjs = require("dcmjs");

async function main() {
    const job = JSON.parse(fs.readFileSync(process.argv[2], "utf8"));
    const t0 = process.hrtime.bigint();
    const datasets = job.ctFiles.map((file) => {
        const b = fs.readFileSync(file);
        const dicom = dcmjs.data.DicomMessage.readFile(
            b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength));
        const ds = dcmjs.data.DicomMetaDictionary.naturalizeDataset(dicom.dict);
        ds._meta = dcmjs.data.DicomMetaDictionary.namifyDataset(dicom.meta);
        return ds;
    });
    const t1 = process.hrtime.bigint();
    const multiframe = dcmjs.normalizers.Normalizer.normalizeToDataset(datasets);
    const seg = new dcmjs.derivations.Segmentation([multiframe]);
    const tDerived = process.hrtime.bigint();
    const sliceOf = new Map(job.sliceUids.map((uid, k) => [uid, k]));
    let refs = multiframe.ReferencedSeriesSequence.ReferencedInstanceSequence;
    refs = Array.isArray(refs) ? refs : [refs];
    const frameSlice = refs.map((r) => sliceOf.get(r.ReferencedSOPInstanceUID));
    if (frameSlice.some((k) => k === undefined)) {
        throw new Error("a frame of the normalized CT is no slice of the job's grid");
    }
    const plane = job.rows * job.columns;
    const code = (c) => ({CodeValue: c.value, CodingSchemeDesignator: c.scheme, CodeMeaning: c.meaning});
    // One labelmap per segment, as OHIF passes overlapping segments.
    const labelmaps3D = job.segments.map((s) => {
        const bits = fs.readFileSync(s.maskFile);
        const labelmaps2D = [];
        frameSlice.forEach((k, f) => {
            const pixels = new Uint16Array(plane);
            let any = false;
            for (let p = 0; p < plane; ++p) {
                const bit = k * plane + p;
                if ((bits[bit >> 3] >> (bit & 7)) & 1) {
                    pixels[p] = 1;
                    any = true;
                }
            }
            if (any) {
                labelmaps2D[f] = {pixelData: pixels, segmentsOnLabelmap: [1]};
            }
        });
        const meta = {
            SegmentLabel: s.label,
            SegmentedPropertyCategoryCodeSequence: code(s.category),
            SegmentedPropertyTypeCodeSequence: code(s.type),
            SegmentAlgorithmType: s.algorithmType,
            RecommendedDisplayCIELabValue: s.lab,
        };
        if (s.algorithmType !== "MANUAL") {
            meta.SegmentAlgorithmName = s.algorithmName;
        }
        return {labelmaps2D, metadata: [null, meta]};
    });
    const t2 = process.hrtime.bigint();
    const blob = dcmjs.adapters.Cornerstone.Segmentation.fillSegmentation(
        seg, labelmaps3D, {rleEncode: job.rle === true});
    const bytes = Buffer.from(await blob.arrayBuffer());
    const t3 = process.hrtime.bigint();
    fs.writeFileSync(job.output, bytes);
    const ms = (a, b) => Number(b - a) / 1e6;
    // writeMs: what dcmjs does (normalize, derive, fill, encode), not the bits turned into
    // the labelmaps OHIF would already hold.
    process.stdout.write(JSON.stringify({parseMs: ms(t0, t1),
                                         writeMs: ms(t1, tDerived) + ms(t2, t3)}) + "\n");
}

main().catch((e) => {
    process.stderr.write("write-seg.js: " + (e && e.stack ? e.stack : e) + "\n");
    process.exit(1);
});
