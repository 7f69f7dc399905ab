"""onbottom.report."""
