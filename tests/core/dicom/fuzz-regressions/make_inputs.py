#!/usr/bin/env python3
"""Makes the inputs of test_dicom_fuzz_regressions in OUT_DIR: each is a
synthetic seed of fuzz/seeds/make_seeds.py, or a file of the shared real data
("shared:" and its path under DATA_DIR), with the bytes that fuzz_dicom changed
(inputs.json: the seed, then [start, end, new bytes in hex] edits of the seed's
bytes). The repository holds no DICOM files; these are rebuilt, byte for byte,
at build time; those of shared data only where it is there (their tests skip
without it). Usage: make_inputs.py OUT_DIR [DATA_DIR]"""
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
    data_dir = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else None
    inputs = json.loads((HERE / "inputs.json").read_text())
    with tempfile.TemporaryDirectory() as tmp:
        make_seeds.dicom_seeds(pathlib.Path(tmp))
        for name, spec in inputs.items():
            seed = spec["seed"]
            if seed.startswith("shared:"):
                seed_path = data_dir / seed[len("shared:"):] if data_dir else None
                if seed_path is None or not seed_path.is_file():
                    continue
            else:
                seed_path = pathlib.Path(tmp) / seed
            data = bytearray(seed_path.read_bytes())
            for start, end, new in reversed(spec["edits"]):
                data[start:end] = bytes.fromhex(new)
            (out / name).write_bytes(bytes(data))


if __name__ == "__main__":
    main()
