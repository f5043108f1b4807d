"""Maps the top-level data folders into the installed package.

`resources/`, `worlds/` and `plans/` live at the top of the repository (where
people look for them) and are installed as `pycram_cli/_bundled/<name>`, so a
regular `pip install .` finds them; `pycram_cli.paths` looks in both places.
"""
from pathlib import Path

from setuptools import find_packages, setup

HERE = Path(__file__).resolve().parent
BUNDLED = tuple(name for name in ("resources", "worlds", "plans") if (HERE / name).is_dir())

setup(
    packages=find_packages(include=["pycram_cli", "pycram_cli.*"])
    + [f"pycram_cli._bundled.{name}" for name in BUNDLED],
    package_dir={"pycram_cli": "pycram_cli"}
    | {f"pycram_cli._bundled.{name}": name for name in BUNDLED},
    package_data={f"pycram_cli._bundled.{name}": ["**/*"] for name in BUNDLED}
    | {"pycram_cli.report": ["assets/*"]},
    include_package_data=False,
)
