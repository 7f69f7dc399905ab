"""Inputs: immutable, validated descriptions of what the engineer specifies."""

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
