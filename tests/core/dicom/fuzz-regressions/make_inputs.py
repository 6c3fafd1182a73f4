#!/usr/bin/env python3
"""Makes the inputs of test_dicom_fuzz_regressions in OUT_DIR: each is a
synthetic seed of fuzz/seeds/make_seeds.py with the bytes that fuzz_dicom
changed (inputs.json: the seed, then [start, end, new bytes in hex] edits of
the seed's bytes). The repository holds no DICOM files; these are rebuilt,
byte for byte, at build time. Usage: make_inputs.py OUT_DIR"""
import json
import pathlib
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[3] / "fuzz" / "seeds"))
import make_seeds  # noqa: E402


def main():
    out = pathlib.Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    inputs = json.loads((HERE / "inputs.json").read_text())
    with tempfile.TemporaryDirectory() as tmp:
        make_seeds.dicom_seeds(pathlib.Path(tmp))
        for name, spec in inputs.items():
            data = bytearray((pathlib.Path(tmp) / spec["seed"]).read_bytes())
            for start, end, new in reversed(spec["edits"]):
                data[start:end] = bytes.fromhex(new)
            (out / name).write_bytes(bytes(data))


if __name__ == "__main__":
    main()
