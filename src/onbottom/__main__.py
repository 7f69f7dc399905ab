"""``python -m onbottom`` runs the CLI."""

import sys

from onbottom.cli.main import main

sys.exit(main())
