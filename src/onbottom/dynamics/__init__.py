"""onbottom.dynamics."""
