"""``python -m onbottom`` runs the CLI."""

import sys

try:
    from onbottom.cli.main import main
except KeyboardInterrupt:  # Ctrl-C while the CLI loads: one line and status 130, as in a run
    sys.stderr.write("interrupted\n")
    sys.exit(130)

sys.exit(main())
