"""The column layout of the pipeline FE's node array (public).

:meth:`onbottom.dynamics.pipeline.PipelineModel.arrays` returns, under ``"nodes"``, a float64
array of shape (n_nodes, :data:`N_NODE_COLS`) with one row per node; the pipeline kernel reads
it and other programs solving the same model (:mod:`onbottom.peers`) read their node masses and
tributary lengths from it. The columns (same constants as the kernel's, re-exported from its
private module so that there is one definition):

- ``ND_X0`` initial position along the pipe axis x [m];
- ``ND_TRIB`` tributary length ℓ of the node [m];
- ``ND_MASS_U`` lumped axial mass [kg];
- ``ND_MASS_V`` lumped lateral mass, added mass included [kg];
- ``ND_J`` rotary inertia about the vertical [kg·m²];
- ``ND_CURRENT`` steady current normal to the pipe [m/s];
- ``ND_MU_AX`` axial friction coefficient μ_ax [-];
- ``ND_WS`` submerged weight [N/m];
- ``ND_R_TR_Y``, ``ND_R_TR_Z`` trench load reductions r_tr,y, r_tr,z [-] (DNV-RP-F109).
"""

from __future__ import annotations

from onbottom.dynamics.pipeline._pipeline_kernel import (
    N_NODE_COLS,
    ND_CURRENT,
    ND_J,
    ND_MASS_U,
    ND_MASS_V,
    ND_MU_AX,
    ND_R_TR_Y,
    ND_R_TR_Z,
    ND_TRIB,
    ND_WS,
    ND_X0,
)

__all__ = [
    "ND_CURRENT",
    "ND_J",
    "ND_MASS_U",
    "ND_MASS_V",
    "ND_MU_AX",
    "ND_R_TR_Y",
    "ND_R_TR_Z",
    "ND_TRIB",
    "ND_WS",
    "ND_X0",
    "N_NODE_COLS",
]
