"""Inputs: immutable, validated descriptions of what the engineer specifies."""

from onbottom.inputs.pipe import Layer, Pipe
from onbottom.inputs.soil import Clay, Rock, Sand, Seabed

__all__ = ["Clay", "Layer", "Pipe", "Rock", "Sand", "Seabed"]
