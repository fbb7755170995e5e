"""``python -m lkverify`` is the ``lkverify`` command."""

import sys

from .cli import main

sys.exit(main())
