"""A `project` node's own way to choose: an arithmetic expression over each alternative's outcomes.

    choose: {max: rate - 0.01 * steps}    # the most successful, a step's cost weighed in
    choose: {min: failed}                 # the fewest failures

Why an expression: the named ways (most-successful, first-success, fewest-steps) weigh one number
each; a user trading success against effort says how in one line. Why not Python's `eval`: a plan
is data from a file, and an expression may only do arithmetic on the outcomes. So the text is
parsed with `ast` once, when the plan is read (a bad name is an error there, with a suggestion),
and only numbers, the outcome names below, + - * / and min, max and abs are allowed.
"""
from __future__ import annotations

import ast
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

#: the names an expression may use: one alternative's row of the projection table
OUTCOMES = {
    "rate": "the fraction of its runs that succeeded (0 to 1)",
    "succeeded": "how many of its runs succeeded",
    "failed": "how many of its runs failed",
    "runs": "how many of its runs could start",
    "steps": "the mean number of steps of its successful runs",
}
SENSES = ("max", "min")
FUNCTIONS: dict[str, Callable[..., float]] = {"min": min, "max": max, "abs": abs}
_OPERATORS = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b, ast.Mult: lambda a, b: a * b,
              ast.Div: lambda a, b: a / b if b else math.inf if a > 0 else -math.inf if a < 0 else 0.0}


class ScoreError(ValueError):
    """What is wrong with an expression, and the name meant (for a misspelt one)."""

    def __init__(self, message: str, name: str | None = None) -> None:
        super().__init__(message)
        self.name = name


@dataclass(frozen=True)
class Score:
    """`max` or `min` of an expression over an alternative's outcomes."""

    sense: str
    text: str
    tree: ast.expr

    def of(self, row: Mapping[str, Any]) -> float:
        """The expression's value for one alternative's row (its counts and rate)."""
        values = {"rate": row["rate"] or 0.0, "succeeded": row["succeeded"], "runs": row["runs"],
                  "failed": row["runs"] - row["succeeded"], "steps": row["steps"] or 0.0}
        return float(_evaluate(self.tree, values))

    def describe(self) -> str:
        return f"{self.sense}: {self.text}"


def parse_score(sense: str, text: str) -> Score:
    """The expression `text` to be maximised (`max`) or minimised (`min`); ScoreError when it is not one."""
    if sense not in SENSES:
        raise ScoreError(f"expected max or min, got '{sense}'")
    try:
        tree = ast.parse(text.strip(), mode="eval").body
    except SyntaxError as exc:
        raise ScoreError(f"not an arithmetic expression: {exc.msg}") from None
    _check(tree)
    return Score(sense, text.strip(), tree)


def _check(node: ast.expr) -> None:
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        return
    if isinstance(node, ast.Name):
        if node.id not in OUTCOMES:
            raise ScoreError(f"unknown name '{node.id}'", node.id)
        return
    if isinstance(node, ast.BinOp) and type(node.op) in _OPERATORS:
        _check(node.left)
        _check(node.right)
        return
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        _check(node.operand)
        return
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in FUNCTIONS \
            and node.args and not node.keywords:
        for arg in node.args:
            _check(arg)
        return
    raise ScoreError(f"only numbers, {', '.join(OUTCOMES)}, + - * / and {', '.join(FUNCTIONS)}() are allowed, "
                     f"got '{ast.unparse(node)}'")


def _evaluate(node: ast.expr, values: Mapping[str, float]) -> float:
    if isinstance(node, ast.Constant):
        assert isinstance(node.value, (int, float)), "_check lets only numbers through"
        return float(node.value)
    if isinstance(node, ast.Name):
        return float(values[node.id])
    if isinstance(node, ast.BinOp):
        return _OPERATORS[type(node.op)](_evaluate(node.left, values), _evaluate(node.right, values))
    if isinstance(node, ast.UnaryOp):
        value = _evaluate(node.operand, values)
        return -value if isinstance(node.op, ast.USub) else value
    assert isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
    args = [_evaluate(arg, values) for arg in node.args]
    function = FUNCTIONS[node.func.id]
    return float(function(*args) if node.func.id != "abs" else abs(args[0]))
