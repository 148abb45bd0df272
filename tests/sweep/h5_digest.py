# SPDX-License-Identifier: BSD-3-Clause
"""Prints, as JSON, the SHA-256 of every dataset's bytes in a sweep's results file and the
values the tests look at. Run by /usr/bin/python3 (Debian's h5py), for the tests, whose own
interpreter may lack h5py:  h5_digest.py FILE.h5"""

import hashlib
import json
import sys

import h5py
import numpy


def main(path: str) -> None:
    with h5py.File(path, "r") as results:
        digests = {name: hashlib.sha256(numpy.ascontiguousarray(results[name][()]).tobytes())
                   .hexdigest() for name in results}
        status_names = {value: name for name, value in
                        h5py.check_enum_dtype(results["status"].dtype).items()}
        report = {
            "datasets": digests,
            "shapes": {name: list(results[name].shape) for name in results},
            "status": [status_names[int(s)] for s in results["status"][()]],
            "error": [e.decode() for e in results["error"][()]],
            "chunk_done": [int(d) for d in results["chunk_done"][()]],
            "attributes": sorted(results.attrs),
            "banner": results.attrs["banner"].decode(),
            "sweep": results.attrs["sweep"].decode(),
        }
        for name in ("final_q", "final_v", "trajectory_q", "energy_drift"):
            if name in results:
                report[name] = results[name][()].tolist()
        report["speeds"] = [s.decode() for s in results.attrs["speeds"]]
    json.dump(report, sys.stdout)


if __name__ == "__main__":
    main(sys.argv[1])
