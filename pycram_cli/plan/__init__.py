"""Plans: CRAM-style robot programs written in YAML, validated, run, and traced.

    from pycram_cli.plan import load_plan, run_plan
    plan = load_plan("plans/set_table.yaml")          # InputErrors with file:line:column on problems
    result = run_plan(plan, world, {"object": "milk"})
    result.status, result.failure, result.trace

Modules: `syntax` (YAML to nodes, node registry), `validate` (static checks), `context`
(variables and `$references`), `composites` (seq, par, pursue, try_all, try_in_order),
`decorators` (retry, try/catch, if, unless, for_each), `leaves` (designators, queries,
call, fail, assert, log, set, wait), `scheduler` (threads' turns, cancellation),
`resources` (which branches may run side by side), `executor` (running), `trace`
(trace model, JSON, diff), `params` (`-p` values, finding worlds and plans), `golden`
(golden traces of the bundled plans).
"""
from .executor import RunResult, run_plan
from .params import bind_params, find_plan, parse_assignments, plan_world
from .syntax import NODE_TYPES, Plan, parse_plan
from .validate import check_plan, load_plan

__all__ = ["NODE_TYPES", "Plan", "RunResult", "bind_params", "check_plan", "find_plan", "load_plan",
           "parse_assignments", "parse_plan", "plan_world", "run_plan"]
