"""onbottom.hydro."""
