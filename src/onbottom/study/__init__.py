"""onbottom.study."""
