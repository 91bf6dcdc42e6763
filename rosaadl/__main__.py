"""``python -m rosaadl`` runs the command line."""

import sys

from rosaadl.cli import main

sys.exit(main())
