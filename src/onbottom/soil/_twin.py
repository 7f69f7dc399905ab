"""Plain-Python twins of numba kernels built from the same source (private).

:func:`pure_python` lives in the base module :mod:`onbottom._jit` (the kernels of every
package use it); this module keeps the soil kernels' import of it.
"""

from __future__ import annotations

from onbottom._jit import pure_python

__all__ = ["pure_python"]
