"""Write examples/hindcast_ndbc_44007.csv: ten years of hourly sea states measured by NOAA's
National Data Buoy Center buoy 44007 (off Portland, Maine, 1996–2005), in onbottom's hindcast
schema.

    python3 tools/ndbc_to_hindcast.py A.txt [OUT.csv]
    python3 tools/ndbc_to_hindcast.py --stdmet OUT.csv 44007h2006.txt ... 44007h2017.txt

The second form reads NDBC's standard meteorological files directly (the 2006–2017 record,
``examples/hindcast_ndbc_44007_2006_2017.csv``), with the same T_p assumption.

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


def read_stdmet(paths: list[str | Path]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(time datetime64[s], H_s [m], APD [s]) of NDBC standard meteorological files
    (``44007hYYYY.txt``: columns YY MM DD hh [mm] ... WVHT DPD APD ...; 99.00 is missing, a
    zero is invalid),
    each time rounded to the nearest hour (the buoy reports at hh:50 from 2007), the first
    record of an hour kept."""
    times, hs, apd = [], [], []
    for path in paths:
        with Path(path).open(encoding="utf-8") as fh:
            head = fh.readline().lstrip("#").split()
            iw, ia = head.index("WVHT"), head.index("APD")
            has_min = head[4] == "mm"
            for line in fh:
                if line.startswith("#") or not line.strip():
                    continue
                f = line.split()
                y, mo, d, hr = (int(v) for v in f[:4])
                mi = int(f[4]) if has_min else 0
                t = np.datetime64(f"{y:04d}-{mo:02d}-{d:02d}T{hr:02d}:00:00", "s")
                times.append(t + np.timedelta64(3600 if mi >= 30 else 0, "s"))
                h, a = float(f[iw]), float(f[ia])
                hs.append(h if 0.0 < h < 99.0 else np.nan)  # 99.00: missing; 0: invalid
                apd.append(a if 0.0 < a < 99.0 else np.nan)
    t = np.array(times)
    order = np.argsort(t, kind="stable")
    t, h, a = t[order], np.array(hs)[order], np.array(apd)[order]
    keep = np.concatenate(([True], t[1:] != t[:-1])) & np.isfinite(h) & np.isfinite(a)
    return t[keep], h[keep], a[keep]


def main_stdmet(out: str, *paths: str) -> Path:
    """Convert NDBC stdmet files (``--stdmet OUT.csv FILE...``) and write; returns the path."""
    t, hs, apd = read_stdmet(list(paths))
    step = np.timedelta64(3600, "s")
    grid = np.arange(t[0], t[-1] + step, step)
    k = ((t - t[0]) // step).astype(np.int64)
    h_all = np.full(grid.size, np.nan)
    tp_all = np.full(grid.size, np.nan)
    h_all[k] = hs
    tp_all[k] = apd / TZ_OVER_TP
    missing = int(np.count_nonzero(np.isnan(h_all)))
    y0, y1 = str(grid[0])[:4], str(grid[-1])[:4]
    comments = (
        "Measured sea states: NOAA National Data Buoy Center buoy 44007 (off Portland, Maine),"
        f" hourly, {y0}-{y1}.",
        "Source: NDBC standard meteorological data, files 44007hYYYY.txt (ndbc.noaa.gov"
        " historical data; copies in github.com/USM-PODS/zander-PODS 44007/).",
        "Licence: NDBC data, a work of the US Government: public domain in the US (17 U.S.C."
        " 105); NDBC terms of use apply.",
        f"Processing (tools/ndbc_to_hindcast.py --stdmet): times rounded to the hour, regular"
        f" hourly grid, {missing} hours without a valid WVHT and APD written as missing rows;",
        f"H_s = WVHT; T_p = APD / {TZ_OVER_TP:.4f} (as the 1996-2005 file: APD is the benchmark's"
        " T_z; JONSWAP, gamma = 3.3, DNV-RP-C205 3.5.5: an assumption); no direction, no current.",
    )
    return write_hindcast_csv(out, {"time": grid, "hs": h_all, "tp": tp_all}, comments=comments)


if __name__ == "__main__":
    if sys.argv[1:2] == ["--stdmet"]:
        print(main_stdmet(*sys.argv[2:]))
    else:
        print(main(*sys.argv[1:]))
