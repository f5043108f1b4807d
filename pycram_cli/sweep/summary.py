"""What a sweep found: success rate with its 95 % interval, failures by type and node, time per
scenario, and with `--compare` which alternative succeeds most and where they differ."""
from __future__ import annotations

import math
import statistics
from collections import Counter, defaultdict
from typing import Any

Z95 = 1.959964


def wilson(successes: int, runs: int, z: float = Z95) -> tuple[float, float]:
    """The Wilson score interval of a success rate (95 % by default); (0, 1) when nothing ran."""
    if runs == 0:
        return (0.0, 1.0)
    p = successes / runs
    denominator = 1 + z * z / runs
    centre = (p + z * z / (2 * runs)) / denominator
    half = z * math.sqrt(p * (1 - p) / runs + z * z / (4 * runs * runs)) / denominator
    return (max(0.0, centre - half), min(1.0, centre + half))


#: the status of a scenario no draw of which could start (sweep/worker.py): not a run of the plan
INVALID = "invalid"


def _rate(records: list[dict[str, Any]]) -> dict[str, Any]:
    """Successes among the runs; scenarios that could not start (INVALID) are not runs of the plan."""
    records = [r for r in records if r["status"] != INVALID]
    runs = len(records)
    succeeded = sum(1 for r in records if r["status"] == "succeeded")
    lo, hi = wilson(succeeded, runs)
    return {"runs": runs, "succeeded": succeeded, "rate": round(succeeded / runs, 4) if runs else None,
            "interval": [round(lo, 4), round(hi, 4)]}


def outcome_of(record: dict[str, Any]) -> str:
    """`succeeded`, or the failure type (Timeout and InternalError included)."""
    if record["status"] == "succeeded":
        return "succeeded"
    return (record.get("failure") or {}).get("type") or record["status"]


def summarise(records: list[dict[str, Any]], meta: dict[str, Any]) -> dict[str, Any]:
    summary: dict[str, Any] = {"plan": meta.get("plan"), "world": meta.get("world"), "vary": meta.get("vary"),
                               "seed": meta.get("seed"), "scenarios": len({r["index"] for r in records})}
    summary.update(_rate(records))
    summary["statuses"] = dict(sorted(Counter(r["status"] for r in records).items()))
    groups: dict[tuple[str, str | None], list[dict[str, Any]]] = defaultdict(list)
    for record in records:
        if record["status"] not in ("succeeded", INVALID):
            failure = record.get("failure") or {}
            groups[(failure.get("type") or record["status"], failure.get("path"))].append(record)
    failures = []
    for (kind, path), members in sorted(groups.items(), key=lambda item: (-len(item[1]), item[0][0], item[0][1] or "")):
        example = min(members, key=lambda r: (r["index"], r.get("alternative") is not None))
        failures.append({"type": kind, "path": path, "count": len(members),
                         "example": {"index": example["index"], "seed": example["seed"],
                                     **({"alternative": example["alternative"]} if "alternative" in example else {}),
                                     "message": (example.get("failure") or {}).get("message")}})
    summary["failures"] = failures
    summary["starts"] = _starts(records)
    durations = [r["timing"]["duration"] for r in records if r.get("timing")]
    setups = [r["timing"].get("setup", 0.0) for r in records if r.get("timing")]
    summary["time"] = {"median": round(statistics.median(durations), 4) if durations else None,
                       "mean": round(statistics.fmean(durations), 4) if durations else None,
                       "setup_median": round(statistics.median(setups), 5) if setups else None}
    alternatives = (meta.get("compare") or {}).get("alternatives")
    if alternatives:
        summary["compare"] = compare(records, meta["compare"]["param"], alternatives)
    return summary


def _starts(records: list[dict[str, Any]]) -> dict[str, Any]:
    """How many scenarios were drawn again because a draw could not start (scenario/starts.py), with an example
    reason, and how many no draw made possible (INVALID)."""
    redrawn = [r for r in records if r["status"] != INVALID and (r.get("varied") or {}).get("redrawn")]
    invalid = [r for r in records if r["status"] == INVALID]
    first = min(redrawn, key=lambda r: r["index"], default=None)
    return {"redrawn": len(redrawn), "example": first["varied"]["redrawn"][0] if first else None,
            "invalid": len(invalid),
            "invalid_example": (min(invalid, key=lambda r: r["index"]).get("failure") or {}).get("message")
            if invalid else None}


def compare(records: list[dict[str, Any]], param: str, alternatives: list[dict[str, Any]]) -> dict[str, Any]:
    """Each alternative's rate; the best; the scenarios on which the alternatives' outcomes differ."""
    by_alt = [[r for r in records if r.get("alternative") == alt] for alt in alternatives]
    rows = [{"value": alt[param], **_rate(members)} for alt, members in zip(alternatives, by_alt)]
    ranked = sorted(range(len(rows)), key=lambda i: (-(rows[i]["rate"] or 0.0), i))
    outcomes: dict[int, dict[int, str]] = defaultdict(dict)
    seeds: dict[int, int] = {}
    for i, members in enumerate(by_alt):
        for record in members:
            outcomes[record["index"]][i] = outcome_of(record)
            seeds[record["index"]] = record["seed"]
    differ = []
    for index in sorted(outcomes):
        seen = outcomes[index]
        if len(seen) == len(alternatives) and len(set(seen.values())) > 1:
            differ.append({"index": index, "seed": seeds[index],
                           "outcomes": {str(alternatives[i][param]): seen[i] for i in sorted(seen)}})
    best = rows[ranked[0]] if rows else None
    tied = [rows[i]["value"] for i in ranked if rows[i]["rate"] == (best or {}).get("rate")]
    return {"param": param, "alternatives": rows, "best": best["value"] if best and len(tied) == 1 else None,
            "tied": tied if len(tied) > 1 else [], "differ": differ}
