"""The variable registry of every result: names, long names and units (:data:`VARIABLES`).

Every xarray Dataset that onbottom returns takes the ``long_name`` and ``units`` of its
variables from :data:`VARIABLES` (add an entry when you add a variable) through
:func:`annotate`.
"""

from __future__ import annotations

import xarray as xr

__all__ = ["VARIABLES", "annotate"]

VARIABLES: dict[str, tuple[str, str]] = {
    # name: (long_name, units)
    "time": ("time", "s"),
    # one name per quantity (docs/conventions.md): y lateral, z penetration
    "y": ("lateral displacement of the pipe section", "m"),
    "y_dot": ("lateral velocity of the pipe section", "m/s"),
    "z": ("penetration (embedment) of the pipe invert", "m"),
    "H": ("applied horizontal load per unit length", "N/m"),
    "V": ("vertical contact load per unit length", "N/m"),
    "F_soil": ("total lateral soil resistance on the pipe", "N/m"),
    "F_friction": ("Coulomb friction part of the lateral resistance", "N/m"),
    "F_passive": ("passive part of the lateral resistance", "N/m"),
    "work": ("accumulated work in the current trough", "N"),
    "region": ("displacement region of the soil model", "1"),
    "Q_v": ("vertical penetration resistance per unit length", "N/m"),
    "z_over_D": ("normalised penetration z/D", "1"),
    "B": ("contact width of the pipe at the seabed", "m"),
    "Q_v_lower": ("lower estimate of the vertical penetration resistance", "N/m"),
    "Q_v_upper": ("upper estimate of the vertical penetration resistance", "N/m"),
    "soil_energy_stored": ("elastic energy stored in the soil springs", "J/m"),
    "soil_energy_dissipated": ("energy dissipated by the soil since the start", "J/m"),
    "peak_time": ("time of the peak horizontal load of a wave cycle", "s"),
    "H_peak": ("peak horizontal hydrodynamic load |F_Y| of a wave cycle", "N/m"),
    "F_Z_peak": ("lift at the peak horizontal load of a wave cycle", "N/m"),
    "V_peak": ("vertical contact load w_s - F_Z at the peak of a wave cycle", "N/m"),
    "load_angle": ("load angle atan(H/V) from the V axis at the peak of a wave cycle", "degree"),
    "fraction_20_45": ("fraction of wave cycles with load angle in [20, 45] degrees", "1"),
    "w_s": ("submerged weight of the pipe per unit length", "N/m"),
    # storm section
    "F_hydro": ("horizontal hydrodynamic load on the pipe F_Y", "N/m"),
    "F_Z": ("hydrodynamic lift on the pipe", "N/m"),
    "U": ("wave-induced near-bed velocity normal to the pipe", "m/s"),
    "work_hydro": ("work of the hydrodynamic load on the pipe", "J/m"),
    "work_soil": ("work done by the pipe on the soil", "J/m"),
    "r_y": ("total horizontal load reduction r_tot,y", "1"),
    "r_z": ("total vertical load reduction r_tot,z", "1"),
    # pipeline FE (time × node; onbottom.dynamics.pipeline)
    "u_axial": ("axial displacement of the pipe", "m"),
    "moment": ("bending moment in the horizontal plane", "N m"),
    "axial_force": ("effective axial force (tension positive)", "N"),
    "strain": ("largest longitudinal fibre strain |N|/EA + |M|c/EI", "1"),
}


def annotate(ds: xr.Dataset) -> xr.Dataset:
    """Fill ``long_name``/``units`` of variables and coordinates from :data:`VARIABLES`."""
    for name in list(ds.variables):
        if name in VARIABLES:
            long_name, units = VARIABLES[str(name)]
            ds[name].attrs.setdefault("long_name", long_name)
            ds[name].attrs.setdefault("units", units)
    return ds
