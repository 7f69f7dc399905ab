"""Figure of docs/validation/opensees_peer.md from the envelopes saved by
``benchmarks/opensees_peer.py --save``.

Run: ``python tools/opensees_peer_figure.py newmark.npz hht.npz
docs/validation/figures/opensees_peer_envelopes.png``.
"""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main(paths: list[str], out: str) -> None:
    fig, (ax, ad) = plt.subplots(2, 1, figsize=(7.5, 6.0), sharex=True)
    for p, colour in zip(paths, ("C0", "C3"), strict=False):
        z = np.load(p)
        a = float(z["alpha"])
        label = "Newmark" if a == 0.0 else f"HHT α = {a:g}"
        x, ob, os_ = z["x"], z["onbottom"], z["opensees"]
        ax.plot(x, ob, color=colour, lw=1.2, label=f"onbottom, {label}")
        ax.plot(x[::10], os_[::10], "o", ms=3.5, mfc="none", color=colour,
                label=f"OpenSees, {label}")  # fmt: skip
        rel = np.abs(ob - os_) / np.max(os_)
        ad.semilogy(x, np.maximum(rel, 1e-12), color=colour, lw=1.0, label=label)
    ax.set_ylabel("max |y| [m]")
    ax.legend(fontsize=8, ncol=2)
    ax.grid(alpha=0.3)
    ad.set_ylabel("|Δ envelope| / max |y|")
    ad.set_xlabel("x [m]")
    ad.axhline(1e-4, color="C0", ls="--", lw=0.8)
    ad.axhline(5e-3, color="C3", ls="--", lw=0.8)
    ad.grid(alpha=0.3, which="both")
    ad.legend(fontsize=8)
    fig.suptitle("1 km pipeline, 500 corotational elements, ElasticPP springs, 600 s", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1:-1], sys.argv[-1])
