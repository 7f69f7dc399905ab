"""Write examples/hindcast_ndbc_44007.csv: ten years of hourly sea states measured by NOAA's
National Data Buoy Center buoy 44007 (off Portland, Maine, 1996–2005), in onbottom's hindcast
schema.

    python3 tools/ndbc_to_hindcast.py A.txt [OUT.csv]

Input: dataset A of the environmental-contour benchmark (Haselsteiner et al. 2019,
OMAE2019-96523; "A.txt" of github.com/ec-benchmark-organizers/ec-benchmark, also
"ec-benchmark_dataset_A.txt" of github.com/virocon-organization/virocon): lines
``YYYY-MM-DD-HH; H_s [m]; T_z [s]`` — 82 805 hourly NDBC records as the benchmark's organisers
prepared them from the buoy's standard meteorological data.

Licence: NDBC data are a work of the US Government (NOAA), in the public domain in the US
(17 U.S.C. §105); the benchmark's README says the NDBC terms of use apply (ndbc.noaa.gov: freely
available, no restriction on use). The file written here names its source.

Processing, all of it stated in the file's header:

* the times are put on the regular hourly grid from the first to the last record; hours without
  a record are written as **missing** rows (empty values; 4 867 hours, 5.6 %) — not filled;
* T_p = T_z / (T_z/T_p): the JONSWAP ratio T_z/T_p = 0.6673 + 0.05037γ − 0.006230γ² +
  0.0003341γ³ = 0.7777 of DNV-RP-C205 (2019) §3.5.5 at γ = 3.3 — an assumption (a buoy's spectrum is
  not one JONSWAP; the benchmark gives T_z only);
* no wave direction and no current: the buoy's standard record in the benchmark has neither,
  so the record is analysed omnidirectionally (``--sectors 1``) and has no current model.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from onbottom.metocean.hindcast import write_hindcast_csv

GAMMA = 3.3
TZ_OVER_TP = 0.6673 + 0.05037 * GAMMA - 0.006230 * GAMMA**2 + 0.0003341 * GAMMA**3


def read_benchmark(path: str | Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(time datetime64[s], H_s [m], T_z [s]) of a benchmark file."""
    times, hs, tz = [], [], []
    with Path(path).open(encoding="utf-8") as fh:
        next(fh)  # header line
        for line in fh:
            if not line.strip():
                continue
            t, h, z = (p.strip() for p in line.split(";"))
            y, mo, d, hr = t.split("-")
            times.append(np.datetime64(f"{y}-{mo}-{d}T{hr}:00:00", "s"))
            hs.append(float(h))
            tz.append(float(z))
    return np.array(times), np.array(hs), np.array(tz)


def main(src: str, out: str = "examples/hindcast_ndbc_44007.csv") -> Path:
    """Convert and write; returns the path."""
    t, hs, tz = read_benchmark(src)
    step = np.timedelta64(3600, "s")
    grid = np.arange(t[0], t[-1] + step, step)
    k = ((t - t[0]) // step).astype(np.int64)
    h_all = np.full(grid.size, np.nan)
    tp_all = np.full(grid.size, np.nan)
    h_all[k] = hs
    tp_all[k] = tz / TZ_OVER_TP
    missing = int(np.count_nonzero(np.isnan(h_all)))
    comments = (
        "Measured sea states: NOAA National Data Buoy Center buoy 44007 (off Portland, Maine),"
        " hourly, 1996-2005.",
        "Source: dataset A of the environmental-contour benchmark (Haselsteiner et al. 2019,"
        " OMAE2019-96523), github.com/ec-benchmark-organizers/ec-benchmark datasets/A.txt.",
        "Licence: NDBC data, a work of the US Government: public domain in the US (17 U.S.C."
        " 105); NDBC terms of use apply.",
        f"Processing (tools/ndbc_to_hindcast.py): regular hourly grid, {missing} hours without"
        " a record written as missing rows (empty);",
        f"T_p = T_z / {TZ_OVER_TP:.4f} (JONSWAP, gamma = 3.3, DNV-RP-C205 3.5.5: an"
        " assumption); no wave direction, no current in this record.",
    )
    return write_hindcast_csv(out, {"time": grid, "hs": h_all, "tp": tp_all}, comments=comments)


if __name__ == "__main__":
    print(main(*sys.argv[1:]))
