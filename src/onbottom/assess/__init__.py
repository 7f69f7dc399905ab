"""Route assessment (``onbottom assess``): every F109 level on every KP section of a route.

:func:`assess` runs a built :class:`Route` (on Dask) and returns an :class:`Assessment`
(pandas/xarray tables); :func:`~onbottom.assess.output.write_outputs` writes the design report
(HTML, optional PDF), ``results.json`` and the NetCDF of the dynamic runs. A route case file
is read and built by :func:`onbottom.cases.assess.load_route`::

    from onbottom.assess import assess
    from onbottom.cases.assess import load_route

    a = assess(load_route("examples/assess_route.toml"), n_workers=2)
"""

from onbottom.assess.core import Assessment, assess
from onbottom.assess.route import (
    DesignRange,
    DynamicSettings,
    Levels,
    PipelineFESettings,
    Route,
    Section,
    StormCombination,
)

__all__ = [
    "Assessment",
    "DesignRange",
    "DynamicSettings",
    "Levels",
    "PipelineFESettings",
    "Route",
    "Section",
    "StormCombination",
    "assess",
]


def __getattr__(name: str) -> object:
    if name == "PipelineSettings":
        import warnings

        warnings.warn(
            "onbottom.assess.PipelineSettings is renamed PipelineFESettings (the pipeline FE"
            " solver's own settings are onbottom.dynamics.pipeline.PipelineSettings); the old"
            " name goes in the next release",
            DeprecationWarning,
            stacklevel=2,
        )
        return PipelineFESettings
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
