"""Every example script runs to completion and prints its key result (scikit-fem style).

One test per example (``test_example_runs[ex07_dem_penetration.py]``), so ``-v`` shows each as
it ends; with ``-s`` each also prints ``example NAME: T s``. The examples run the checkout's
``src/`` (``PYTHONPATH``), installed or not. Marked ``long`` (``python3 -m pytest -m long``).
"""

from __future__ import annotations

import os
import pathlib
import re
import subprocess
import sys
import time

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"

# script → a regular expression its output must match (one key number each)
EXPECTED = {
    "ex01_soil_models.py": r"penetration: z_i = 0\.1168 m",
    "ex02_f114_penetration.py": r"z/D = 0\.1: Q_v = +33\.0 kN/m",
    "ex03_section_time_domain.py": r"cycles to the 3 m limit: 1[23]\.\d\d",
    "ex06_calibrate_verley_sotberg.py": r"C += 0\.7[89]\d\d",
    "ex07_dem_penetration.py": r"inertial number I = ",
    "ex08_f109_design.py": r"absolute lateral stability: utilisation 4\.\d+ \(fails\)",
    "ex09_storm_section.py": (
        r"max \|y\| = \d+\.\d{3} m = \d+\.\d{3}D\n.*\n.*\nF109 0\.5D: (pass|fail)"
    ),
    "ex10_metocean_reliability.py": r"importance sampling: p per storm = 0\.000[89]\d\d \(CV",
    "ex11_route_assessment.py": r"mid-route\s+35\s+1\.373",
}


def test_every_example_is_covered():
    assert sorted(p.name for p in EXAMPLES.glob("ex*.py")) == sorted(EXPECTED)


@pytest.mark.slow
@pytest.mark.long
@pytest.mark.parametrize("script", sorted(EXPECTED))
def test_example_runs(script, tmp_path):
    path = os.pathsep.join(p for p in (str(ROOT / "src"), os.environ.get("PYTHONPATH")) if p)
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=path)
    t0 = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, str(EXAMPLES / script)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        env=env,
        check=False,
    )
    print(f"example {script}: {time.perf_counter() - t0:.1f} s")  # progress, shown with -s
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert re.search(EXPECTED[script], proc.stdout), proc.stdout[-2000:]
