"""onbottom.soil."""
