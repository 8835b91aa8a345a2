"""``python -m demos``: list the demos, or run one (see demos/cli.py)."""

from demos.cli import main

raise SystemExit(main())
