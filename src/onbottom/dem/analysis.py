"""Post-processing of DEM states: measuring circles, surface profile, inertial number.

Model-scale SI units, unit out-of-plane thickness (stresses in Pa).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from onbottom.constants import GRAVITY

__all__ = [
    "band_to_surface",
    "band_void_ratio",
    "circle_disk_overlap_area",
    "inertial_number",
    "measuring_circles",
    "rotated_clusters",
    "surface_profile",
]


def circle_disk_overlap_area(
    xc: float, yc: float, rc: float, x: np.ndarray, y: np.ndarray, r: np.ndarray
) -> np.ndarray:
    """Exact intersection area of the circle (xc, yc, rc) with each disk (x, y, r) [m²]."""
    d = np.hypot(x - xc, y - yc)
    r = np.asarray(r, float)
    out = np.zeros_like(d)
    inside = d <= np.abs(rc - r)
    out[inside] = np.pi * np.minimum(rc, r[inside]) ** 2
    part = (d < rc + r) & ~inside
    if np.any(part):
        dd = d[part]
        rr = r[part]
        a1 = rr**2 * np.arccos(np.clip((dd**2 + rr**2 - rc**2) / (2 * dd * rr), -1, 1))
        a2 = rc**2 * np.arccos(np.clip((dd**2 + rc**2 - rr**2) / (2 * dd * rc), -1, 1))
        a3 = 0.5 * np.sqrt(
            np.clip((-dd + rr + rc) * (dd + rr - rc) * (dd - rr + rc) * (dd + rr + rc), 0, None)
        )
        out[part] = a1 + a2 - a3
    return out


def _segment_area_below(y_cut: np.ndarray, y: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Area of each disk below the horizontal line ``y_cut`` [m²]."""
    h = np.clip(y_cut - (y - r), 0.0, 2.0 * r)  # height of the part below the line
    # circular segment of height h: r² acos((r−h)/r) − (r−h)√(2rh − h²)
    c = np.clip((r - h) / r, -1.0, 1.0)
    return r**2 * np.arccos(c) - (r - h) * np.sqrt(np.clip(2 * r * h - h * h, 0, None))


def band_void_ratio(
    positions: np.ndarray,
    radii: np.ndarray,
    x_range: tuple[float, float],
    y_range: tuple[float, float],
) -> float:
    """2D void ratio of a horizontal band spanning the box width (exact disk clipping) [-].

    ``x_range`` must be the inner box width (disks do not cross the side walls).
    """
    y = positions[:, 1]
    solid = np.sum(
        _segment_area_below(np.full_like(y, y_range[1]), y, radii)
        - _segment_area_below(np.full_like(y, y_range[0]), y, radii)
    )
    total = (x_range[1] - x_range[0]) * (y_range[1] - y_range[0])
    return float((total - solid) / solid)


def surface_profile(
    positions: np.ndarray, radii: np.ndarray, box: tuple[float, ...], bin_width: float
) -> tuple[np.ndarray, np.ndarray]:
    """Soil surface: highest disk top in each bin of width ``bin_width`` [m].

    Returns (bin centres x [m], surface height y [m]; NaN for an empty bin).
    """
    n_bins = max(1, int((box[1] - box[0]) / bin_width))
    edges = np.linspace(box[0], box[1], n_bins + 1)
    idx = np.clip(np.searchsorted(edges, positions[:, 0], side="right") - 1, 0, n_bins - 1)
    tops = np.full(n_bins, -np.inf)
    np.maximum.at(tops, idx, positions[:, 1] + radii)
    tops[~np.isfinite(tops)] = np.nan
    return 0.5 * (edges[1:] + edges[:-1]), tops


def measuring_circles(
    positions: np.ndarray,
    radii: np.ndarray,
    contacts: dict[str, np.ndarray],
    box: tuple[float, ...],
    surface: float,
    diameter: float,
    n_columns: int = 8,
    row_spacing: float | None = None,
) -> xr.Dataset:
    """Porosity, σ_h, σ_v and K0 = σ_h/σ_v from rows of measuring circles.

    Circles of ``diameter`` are laid in rows from ``diameter/2`` below ``surface`` down to the
    bottom, ``row_spacing`` apart (default ``diameter/2``: overlapping rows, for a finer depth
    profile), ``n_columns`` per row spread over the width (one circle diameter clear of the side
    walls); each row is averaged. Porosity from the exact disk–circle intersection areas;
    stress from the contact forces whose contact point lies in the circle (Love–Weber average,
    compression positive): ``σ_ab = (1/A) Σ_c f_a l_b``, with ``l`` the branch vector and
    ``f`` the force carried along it.

    Parameters
    ----------
    contacts
        ``i``, ``j``, ``fn`` [N], ``fs`` [N] of the touching disk pairs.
    surface
        Height of the soil surface [m] (depth origin).
    diameter
        Circle diameter [m] (the paper: 0.5D).
    """
    rc = 0.5 * diameter
    x0, x1, y0 = box[0], box[1], box[2]
    step = 0.5 * diameter if row_spacing is None else row_spacing
    n_rows = max(1, int((surface - y0 - diameter) / step) + 1)
    xs = np.linspace(x0 + diameter, x1 - diameter, n_columns)
    ci, cj = contacts["i"], contacts["j"]
    bx = positions[cj, 0] - positions[ci, 0]
    by = positions[cj, 1] - positions[ci, 1]
    d = np.hypot(bx, by)
    nx, ny = bx / d, by / d
    # force on j from i: fn·n − fs·t with t = (−ny, nx)
    fx = contacts["fn"] * nx + contacts["fs"] * ny
    fy = contacts["fn"] * ny - contacts["fs"] * nx
    ri = radii[ci]
    px = positions[ci, 0] + nx * ri
    py = positions[ci, 1] + ny * ri
    depth = np.empty(n_rows)
    por = np.empty(n_rows)
    sh = np.empty(n_rows)
    sv = np.empty(n_rows)
    npart = np.empty(n_rows)
    for k in range(n_rows):
        yc = surface - rc - k * step
        depth[k] = surface - yc
        p_acc, sh_acc, sv_acc, n_acc = [], [], [], []
        for xc in xs:
            area = math.pi * rc * rc
            solid = circle_disk_overlap_area(xc, yc, rc, positions[:, 0], positions[:, 1], radii)
            p_acc.append(1.0 - solid.sum() / area)
            n_acc.append(
                np.count_nonzero(np.hypot(positions[:, 0] - xc, positions[:, 1] - yc) < rc)
            )
            inside = np.hypot(px - xc, py - yc) < rc
            sh_acc.append(np.sum(fx[inside] * bx[inside]) / area)
            sv_acc.append(np.sum(fy[inside] * by[inside]) / area)
        por[k] = np.mean(p_acc)
        sh[k] = np.mean(sh_acc)
        sv[k] = np.mean(sv_acc)
        npart[k] = np.mean(n_acc)
    ds = xr.Dataset(
        {
            "porosity": ("depth", por, {"long_name": "porosity", "units": "1"}),
            "sigma_h": ("depth", sh, {"long_name": "horizontal stress", "units": "Pa"}),
            "sigma_v": ("depth", sv, {"long_name": "vertical stress", "units": "Pa"}),
            "K0": (
                "depth",
                np.divide(sh, sv, out=np.full_like(sh, np.nan), where=sv != 0.0),
                {
                    "long_name": "lateral earth pressure coefficient",
                    "units": "1",
                    "comment": "NaN where the circles carry no vertical stress (undefined)",
                },
            ),
            "particles_per_circle": (
                "depth",
                npart,
                {"long_name": "disks with centre in a circle", "units": "1"},
            ),
        },
        coords={"depth": ("depth", depth, {"long_name": "depth below surface", "units": "m"})},
    )
    ds.attrs["circle_diameter"] = diameter
    ds.attrs["n_columns"] = n_columns
    ds.attrs["row_spacing"] = step
    return ds


def inertial_number(
    velocity: float,
    height: float,
    d50: float,
    density: float,
    porosity: float,
    gravity_factor: float,
    g: float = GRAVITY,
) -> float:
    """Inertial number of the penetration, I = γ̇·√(m/(P·d50)) [-].

    ``γ̇ = v/H``; ``m = ρ_s·π·d50²/4`` (disk of unit thickness); ``P = ρ_s(1−n)·N·g·H``, the
    overburden at the specimen base. This reading of the paper's Eq. (1)–(2) (Tran et al.)
    reproduces its I = 4.38e-4 for v = 0.01 m/s, H = 0.11 m, d50 = 0.68 mm, e = 0.197, N = 25
    (4.4e-4). Quasi-static when I ≤ 1e-3.
    """
    m = density * math.pi * d50 * d50 / 4.0
    p = density * (1.0 - porosity) * gravity_factor * g * height
    return velocity / height * math.sqrt(m / (p * d50))


def rotated_clusters(
    x: np.ndarray,
    y: np.ndarray,
    radius: np.ndarray,
    rotation: np.ndarray,
    threshold: float,
    neighbour_factor: float = 1.1,
) -> np.ndarray:
    """Clusters of the disks whose |rotation| exceeds ``threshold`` [rad].

    Two such disks are neighbours when their centres are closer than
    ``neighbour_factor``·(r_i + r_j) (touching, or nearly: a contact may open for an instant
    in a shear band). Returns a label per disk: the cluster index (0, 1, …), −1 for a disk
    that did not rotate enough.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    labels = np.full(len(x), -1, int)
    sel = np.nonzero(np.abs(np.asarray(rotation, float)) > threshold)[0]
    if sel.size == 0:
        return labels
    pts = np.column_stack([np.asarray(x, float)[sel], np.asarray(y, float)[sel]])
    r = np.asarray(radius, float)[sel]
    pairs = cKDTree(pts).query_pairs(2.0 * neighbour_factor * float(r.max()), output_type="ndarray")
    if pairs.size:
        d = np.hypot(*(pts[pairs[:, 0]] - pts[pairs[:, 1]]).T)
        pairs = pairs[d < neighbour_factor * (r[pairs[:, 0]] + r[pairs[:, 1]])]
    n = sel.size
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, lab = connected_components(graph, directed=False)
    labels[sel] = lab
    return labels


def band_to_surface(
    x: np.ndarray,
    y: np.ndarray,
    radius: np.ndarray,
    rotation_increment: np.ndarray,
    pipe_x: float,
    pipe_y: float,
    pipe_radius: float,
    d50: float,
    *,
    threshold_deg: float = 10.0,
    neighbour_factor: float = 1.1,
    surface_depth: float = 2.0,
    footprint_ratio: float = 0.75,
) -> dict[str, object]:
    """Does a band of rotating disks join the pipe to the soil surface?

    The disks whose incremental rotation (e.g. between the peak and the trough of a softening
    episode) exceeds ``threshold_deg`` form clusters (:func:`rotated_clusters`). The episode
    *reaches the surface* when one cluster holds

    * a disk in the pipe's contact zone: its gap to the pipe below
      ``(neighbour_factor − 1)``·2·r_i (the neighbour rule's tolerance), and
    * a disk at the soil surface away from the pipe: its top within ``surface_depth``·d50 of
      the surface profile (highest disk top in bins of 2·d50, of the same state) and its centre
      at least ``footprint_ratio``·D from the pipe axis (closer, the surface is the pipe's
      own berm, which any cluster touching the pipe at shallow embedment would reach).

    Parameters
    ----------
    x, y, radius : array
        Disk centres and radii [m] (one state, e.g. the trough's).
    rotation_increment : array
        Rotation of each disk over the interval [rad].
    pipe_x, pipe_y, pipe_radius : float
        Pipe centre and radius [m] in the same state.
    d50 : float
        Median grain diameter [m].

    Returns
    -------
    dict
        ``reaches_surface`` (bool), ``outcrop_x_over_D`` (signed distance from the axis of the
        connecting cluster's surface disk farthest from the pipe, / D; NaN if none),
        ``n_rotated`` (disks above the threshold), ``band_size`` (disks in the largest
        cluster touching the pipe, 0 if none), ``labels`` (cluster label per disk, −1 = not
        rotated) and ``band`` (boolean mask of the connecting cluster(s)).
    """
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    r = np.asarray(radius, float)
    D = 2.0 * pipe_radius
    labels = rotated_clusters(
        x, y, r, rotation_increment, np.radians(threshold_deg), neighbour_factor
    )
    gap = np.hypot(x - pipe_x, y - pipe_y) - pipe_radius - r
    at_pipe = gap < (neighbour_factor - 1.0) * 2.0 * r
    bin_w = 2.0 * d50
    x0 = float(np.min(x - r))
    box = (x0, float(np.max(x + r)) + 1e-12)
    xs, top = surface_profile(np.column_stack([x, y]), r, box, bin_w)
    idx = np.clip(((x - box[0]) / (box[1] - box[0]) * len(xs)).astype(int), 0, len(xs) - 1)
    at_surface = (y + r >= top[idx] - surface_depth * d50) & (
        np.abs(x - pipe_x) >= footprint_ratio * D
    )
    pipe_clusters = set(np.unique(labels[at_pipe & (labels >= 0)]).tolist())
    surf_clusters = set(np.unique(labels[at_surface & (labels >= 0)]).tolist())
    joined = sorted(pipe_clusters & surf_clusters)
    band = np.isin(labels, joined) if joined else np.zeros(len(x), bool)
    outcrop = np.nan
    if joined:
        out = band & at_surface
        k = int(np.argmax(np.abs(x[out] - pipe_x)))
        outcrop = float((x[out][k] - pipe_x) / D)
    sizes = [int(np.count_nonzero(labels == c)) for c in pipe_clusters]
    return {
        "reaches_surface": bool(joined),
        "outcrop_x_over_D": outcrop,
        "n_rotated": int(np.count_nonzero(labels >= 0)),
        "band_size": max(sizes) if sizes else 0,
        "labels": labels,
        "band": band,
    }
