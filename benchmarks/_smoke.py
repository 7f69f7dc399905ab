"""Tiny sizes of the DEM benchmarks' ``--smoke`` runs (CI: the scripts finish and print)."""

from __future__ import annotations

from pathlib import Path


def tiny_dem_config():
    """A DEM case of about a hundred disks: SD-reduced's materials in a 0.06 m × 0.02 m box,
    two layers, the pipe pushed to w/D = 0.05 (the tiny case of the DEM verification tests)."""
    from onbottom.dem.config import SD_REDUCED, Geometry, Loading, Numerics, Preparation

    return SD_REDUCED.replace(
        name="tiny",
        geometry=Geometry(width=0.06, height=0.02, pipe_diameter=0.02),
        preparation=Preparation(n_layers=2, max_settle_time=0.05),
        loading=Loading(gravity_factor=25.0, pipe_velocity=0.1, final_embedment_ratio=0.05),
        numerics=Numerics(subcycle=True),
    )


def tiny_lattice_sample(folder: Path) -> Path:
    """A small settled lattice bed (bench_dem.py's, 2 cm × 1 cm) saved in ``folder``."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_dem import lattice_bed

    path = Path(folder) / "tiny_bed.nc"
    lattice_bed(width=0.02, height=0.01).save(path)
    return path
