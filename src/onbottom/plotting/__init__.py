"""onbottom.plotting."""
