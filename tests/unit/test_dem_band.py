"""Band-to-surface test on hand-built disk arrangements."""

from __future__ import annotations

import numpy as np

from onbottom.dem.analysis import band_to_surface, rotated_clusters

R_DISK = 1.0
PIPE_R = 4.0


PIPE = (0.0, 15.0)  # pipe of D = 8 pressed 4 deep into a bed whose surface is at y = 15


def _bed(theta_deg: float = -40.0, to: tuple[float, float] = (12.0, 14.0)):
    """Square packing of unit disks (d = 2, top at y = 15) around the pipe, with a chain of
    touching disks from the pipe's rim (angle ``theta_deg``) towards ``to``; returns x, y, r
    and the chain mask."""
    i, j = np.meshgrid(np.arange(-15, 16), np.arange(0, 8))
    gx = 2.0 * i.ravel().astype(float)
    gy = 2.0 * j.ravel().astype(float)
    th = np.radians(theta_deg)
    start = np.array(PIPE) + (PIPE_R + R_DISK) * np.array([np.cos(th), np.sin(th)])
    direction = np.asarray(to) - start
    n = int(np.hypot(*direction) // 2.0) + 1
    chain = start + 2.0 * np.arange(n)[:, None] * direction / np.hypot(*direction)
    free = np.hypot(gx - PIPE[0], gy - PIPE[1]) >= PIPE_R + R_DISK
    for cx, cy in chain:
        free &= np.hypot(gx - cx, gy - cy) >= 2.0 * R_DISK
    x = np.concatenate([gx[free], chain[:, 0]])
    y = np.concatenate([gy[free], chain[:, 1]])
    mask = np.zeros(x.size, bool)
    mask[free.sum() :] = True
    return x, y, np.full(x.size, R_DISK), mask


def _check(rot, bed=None, **kw):
    x, y, r, chain = bed if bed is not None else _bed()
    return band_to_surface(x, y, r, rot(x, y, chain), *PIPE, PIPE_R, 2.0 * R_DISK, **kw)


def test_band_from_pipe_to_surface_reaches_it():
    res = _check(lambda x, y, chain: np.radians(20.0) * chain)
    assert res["reaches_surface"]
    x, _, _, chain = _bed()
    assert res["outcrop_x_over_D"] == x[chain].max() / 8.0 > 1.2
    assert res["band_size"] == res["band"].sum() == chain.sum()
    # cw or ccw alike; on the left side the outcrop is negative
    left = _bed(theta_deg=-140.0, to=(-12.0, 14.0))
    res = _check(lambda x, y, chain: -np.radians(20.0) * chain, bed=left)
    assert res["reaches_surface"] and res["outcrop_x_over_D"] < -1.2


def test_isolated_blob_does_not_reach_the_surface():
    def blob(x, y, chain):
        return np.where(np.hypot(x + 16.0, y - 6.0) < 3.0, -0.5, 0.0)

    res = _check(blob)
    assert res["n_rotated"] > 3 and not res["reaches_surface"]
    assert np.isnan(res["outcrop_x_over_D"]) and res["band_size"] == 0


def test_blob_at_the_pipe_only_or_at_the_surface_only_does_not_count():
    # under the pipe
    at_pipe = _check(lambda x, y, chain: 0.5 * (np.hypot(x, y - 8.0) < 3.5))
    assert at_pipe["band_size"] > 0 and not at_pipe["reaches_surface"]
    at_surf = _check(lambda x, y, chain: 0.5 * ((np.abs(x - 20.0) < 3) & (y > 11)))
    assert not at_surf["reaches_surface"]


def test_berm_next_to_the_pipe_is_not_the_surface():
    # rotation only right beside the pipe (within the 0.75 D footprint): not an outcrop
    def berm(x, y, chain):
        return 0.5 * ((np.abs(x) < 5.9) & (y > 9) & ~chain)

    res = _check(berm)
    assert res["band_size"] > 0 and not res["reaches_surface"]
    # the same with no footprint: reaches it (the rule, not the geometry, decides)
    assert _check(berm, footprint_ratio=0.0)["reaches_surface"]


def test_gap_breaks_a_band_and_threshold_applies():
    rot = np.radians(20.0)

    # the band with one link missing (its third disk stays still): two clusters
    def broken(x, y, chain):
        out = rot * chain
        out[np.nonzero(chain)[0][2]] = 0.0
        return out

    assert not _check(broken)["reaches_surface"]
    # below the threshold nothing rotates "enough"
    res = _check(lambda x, y, chain: np.radians(5.0) * chain)
    assert res["n_rotated"] == 0 and not res["reaches_surface"]


def test_clusters_neighbour_rule():
    x = np.array([0.0, 2.1, 4.5, 10.0])
    lab = rotated_clusters(x, np.zeros(4), np.ones(4), np.ones(4), 0.1)
    # 2.1 < 1.1*2 joins 0 and 1; 2.4 > 2.2 leaves 2 alone; 3 far
    assert lab[0] == lab[1] and len({lab[1], lab[2], lab[3]}) == 3
    assert (rotated_clusters(x, np.zeros(4), np.ones(4), np.zeros(4), 0.1) == -1).all()
