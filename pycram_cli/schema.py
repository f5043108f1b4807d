"""Small checks for mappings read from YAML: allowed and required keys, value types.

Every problem becomes an `InputError` at the exact place, with the closest valid key.
"""
from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

from .errors import InputError, Location, did_you_mean, key_text, not_a_name
from .limits import MAX_MAGNITUDE
from .yamlsource import LMap, where_of

TYPE_NAMES = {str: "a string", bool: "true or false", int: "an integer", float: "a number",
              list: "a list", dict: "a mapping"}


def describe(value: Any) -> str:
    if value is None:
        return "nothing (null)"
    if isinstance(value, bool):
        return f"{value!r}".lower()
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return f"a list of {len(value)}"
    if isinstance(value, str):
        return f"the string '{value}'"
    return repr(value)


def key_error(mapping: LMap, key: Any) -> InputError | None:
    """The problem with a key of a mapping of names (slots, arguments, fields) that is not a name, at the key."""
    problem = not_a_name(key)
    if problem is None:
        return None
    return InputError(problem[0], mapping.loc(key), key=key_text(key), suggestion=problem[1])


def names_only(mapping: LMap, errors: list[InputError]) -> LMap:
    """Report each key of a mapping of names that is not a name (null, a number, true) and leave it out,
    so that later checks, which compare and sort names, see names only. Changes `mapping` in place."""
    for key in [k for k in mapping if not isinstance(k, str)]:
        error = key_error(mapping, key)
        if error is not None:
            errors.append(error)
        del mapping[key]
    return mapping


def check_keys(mapping: LMap, allowed: Iterable[str], required: Iterable[str], context: str,
               errors: list[InputError]) -> None:
    allowed = list(allowed)
    for key in mapping:
        error = key_error(mapping, key)
        if error is not None:
            errors.append(error)
        elif key not in allowed:
            errors.append(InputError(f"unknown key '{key}' in {context}", mapping.loc(key), key=str(key),
                                     suggestion=did_you_mean(str(key), allowed)
                                     or f"valid keys: {', '.join(allowed)}"))
    for key in required:
        if key not in mapping:
            errors.append(InputError(f"missing required key '{key}' in {context}", mapping.loc(), key=key))


def string_entry(entry: LMap, allowed: Iterable[str], required: Iterable[str], strings: Iterable[str], context: str,
                  errors: list[InputError]) -> bool:
    """Check a mapping of a list (a swap's model, an attachment): its keys, and that those of `strings` it has are
    strings. True when that added no error."""
    count = len(errors)
    check_keys(entry, allowed, required, context, errors)
    for key in strings:
        if key in entry:
            expect(entry[key], str, entry.loc(key, True), key, errors)
    return len(errors) == count


def is_numeric(value: Any) -> bool:
    """An int or float (not a bool), whatever its size."""
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def is_number(value: Any) -> bool:
    """A number pycram can use: finite and at most MAX_MAGNITUDE (an int or float, not a bool)."""
    return is_numeric(value) and math.isfinite(value) and abs(value) <= MAX_MAGNITUDE


def number_problem(value: Any) -> str | None:
    """Why a numeric value is not usable (not finite, too large), or None."""
    if not is_numeric(value) or is_number(value):
        return None
    if isinstance(value, float) and not math.isfinite(value):
        return f"numbers must be finite, got {value}"
    return f"numbers must be between -{MAX_MAGNITUDE:g} and {MAX_MAGNITUDE:g}, got {value:g}"


def is_vector(value: Any, size: int) -> bool:
    """A list or tuple of exactly `size` finite numbers."""
    return isinstance(value, (list, tuple)) and len(value) == size and all(is_number(v) for v in value)


def number_list(value: Any, size: int | tuple[int, ...], where: Location, key: str,
                errors: list[InputError]) -> list[float] | None:
    sizes = (size,) if isinstance(size, int) else size
    expected = " or ".join(str(s) for s in sizes)
    if not isinstance(value, list):
        errors.append(InputError(f"expected a list of {expected} numbers, got {describe(value)}", where, key=key))
        return None
    if len(value) not in sizes:
        errors.append(InputError(f"expected {expected} numbers, got {len(value)}", where_of(value, where), key=key))
        return None
    bad = [v for v in value if not is_number(v)]
    if bad:
        message = number_problem(bad[0]) or f"expected numbers, got {describe(bad[0])}"
        errors.append(InputError(message, where_of(value, where), key=key))
        return None
    return [float(v) for v in value]


def expect(value: Any, kind: type | tuple[type, ...], where: Location, key: str, errors: list[InputError]) -> bool:
    kinds = kind if isinstance(kind, tuple) else (kind,)
    ok = isinstance(value, kinds) and not (isinstance(value, bool) and bool not in kinds)
    if float in kinds and is_number(value):
        ok = True
    if not ok:
        names = " or ".join(TYPE_NAMES.get(k, k.__name__) for k in kinds)
        problem = number_problem(value) if float in kinds else None
        errors.append(InputError(problem or f"expected {names}, got {describe(value)}", where, key=key))
    return ok


def quaternion(value: Any, where: Location, key: str, errors: list[InputError]) -> list[float] | None:
    q = number_list(value, 4, where, key, errors)
    if q is None:
        if isinstance(value, list) and len(value) == 3:
            errors[-1].suggestion = "orientation is a quaternion x, y, z, w; e.g. [0, 0, 0, 1] for no rotation"
        return None
    norm = math.sqrt(sum(c * c for c in q))
    if abs(norm - 1.0) > 1e-3:
        scaled = ", ".join(f"{c / norm:.4g}" for c in q) if norm > 0 else "0, 0, 0, 1"
        errors.append(InputError(f"quaternion must have unit length, got norm {norm:.4g}", where_of(value, where),
                                 key=key, suggestion=f"normalised: [{scaled}]"))
        return None
    return q
