"""Inputs: immutable, validated descriptions of what the engineer specifies."""

from __future__ import annotations

from typing import TYPE_CHECKING

from onbottom._lazy import attach

if TYPE_CHECKING:  # the same names, for type checkers, mkdocstrings and the layering test
    from onbottom.inputs.pipe import Layer, Pipe
    from onbottom.inputs.pipe_buildup import CONDITIONS, Contents, PipeBuildUp, PipeProperties
    from onbottom.inputs.soil import Clay, Rock, Sand, Seabed

__all__ = [
    "CONDITIONS",
    "Clay",
    "Contents",
    "Layer",
    "Pipe",
    "PipeBuildUp",
    "PipeProperties",
    "Rock",
    "Sand",
    "Seabed",
]

__getattr__, __dir__ = attach(
    __name__,
    {
        "onbottom.inputs.pipe": (
            "Layer",
            "Pipe",
        ),
        "onbottom.inputs.pipe_buildup": (
            "CONDITIONS",
            "Contents",
            "PipeBuildUp",
            "PipeProperties",
        ),
        "onbottom.inputs.soil": (
            "Clay",
            "Rock",
            "Sand",
            "Seabed",
        ),
    },
)
