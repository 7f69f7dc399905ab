"""onbottom.checks."""
