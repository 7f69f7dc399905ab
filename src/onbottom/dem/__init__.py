"""onbottom.dem."""
