"""One JSON-friendly, deterministic form of any value pycram records or prints.

Objects of a world become their names, tuples and sets lists (sets sorted), numpy numbers
and arrays plain numbers and lists, values with a `to_json()` method what it returns, and
floats are rounded (traces compare byte for byte). Non-finite floats, which JSON cannot
hold, become strings ("nan", "inf") in traces or null in command output.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

_STRING = "string"


def jsonable(value: Any, digits: int | None = 6, nonfinite: str | None = _STRING, drop_none: bool = False) -> Any:
    """`value` as JSON-ready data.

    digits: round floats to this many decimals (None: keep them as they are);
    nonfinite: "string" writes nan/inf as strings, None writes them as null;
    drop_none: leave out mapping entries whose value is None (optional slots not given).
    """
    def convert(item: Any) -> Any:
        if _is_numpy_scalar(item):
            return convert(item.item())
        if item is None or isinstance(item, (bool, str, int)):
            return item
        if isinstance(item, float):
            if not math.isfinite(item):
                return str(item) if nonfinite == _STRING else None
            if digits is None:
                return item
            rounded = round(item, digits)
            if rounded == int(rounded) and abs(rounded) < 1e15:
                rounded = float(int(rounded))
            return 0.0 if rounded == 0 else rounded
        if isinstance(item, Mapping):
            return {str(k): convert(v) for k, v in item.items() if not (drop_none and v is None)}
        if isinstance(item, (list, tuple, set, frozenset)):
            items = sorted(item, key=str) if isinstance(item, (set, frozenset)) else item
            return [convert(v) for v in items]
        to_json = getattr(item, "to_json", None)
        if callable(to_json):
            return convert(to_json())
        if hasattr(item, "tolist"):
            return convert(item.tolist())
        name = getattr(item, "name", None)
        if isinstance(name, str):  # an Object of a world (or anything else known by its name)
            return name
        return str(item)

    return convert(value)


def _is_numpy_scalar(value: Any) -> bool:
    return type(value).__module__ == "numpy" and getattr(value, "shape", None) == ()
