"""Command-line interface (thin: parse → call the public API → write)."""
