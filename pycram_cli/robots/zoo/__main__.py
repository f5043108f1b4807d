"""`python -m pycram_cli.robots.zoo 0 1 2 --out /tmp/zoo`: write zoo robots and their kitchen worlds."""
from __future__ import annotations

from .files import main

if __name__ == "__main__":
    raise SystemExit(main())
