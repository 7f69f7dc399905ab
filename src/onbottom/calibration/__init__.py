"""onbottom.calibration."""
