"""Route assessment (``onbottom assess``): every F109 level on every KP section of a route.

:func:`load_route_case` reads a route case file, :func:`assess` runs it (on Dask) and returns
an :class:`Assessment` (pandas/xarray tables); :func:`write_outputs` writes the design report
(HTML, optional PDF), ``results.json`` and the NetCDF of the dynamic runs.
"""

from onbottom.assess.core import Assessment, assess
from onbottom.cases.assess import RouteCase, load_route_case, parse_route_case

__all__ = ["Assessment", "RouteCase", "assess", "load_route_case", "parse_route_case"]
