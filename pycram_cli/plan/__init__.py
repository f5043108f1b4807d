"""Plans: CRAM-style robot programs written in YAML, validated, run, and traced.

    from pycram_cli.plan import load_plan, run_plan
    plan = load_plan("plans/set_table.yaml")          # InputErrors with file:line:column on problems
    result = run_plan(plan, world, {"object": "milk"})
    result.status, result.failure, result.trace

The package has two floors; the lower never imports the upper (tests/test_architecture.py
checks this, and that no module of the package imports another in a cycle).

The language floor: what a plan is and what it means, without running it.
    `context`     values: `$references`, evaluation, interpolation, variable frames
    `runtime`     the contract with the running floor: the `Runtime` (`ex`), `Record` (`tn`)
                  and `Decider` protocols a node executes against, `Cancelled`, `close_pending`
    `syntax`      YAML to nodes: the `Node` base class, the `Parser`, the node registry, `Plan`
    `resources`   which robot resources (base, arms, head) steps use, statically
    `composites`  seq, par, pursue, try_all, try_in_order; the concurrent ones own their policy
    `leaves`      designators, queries, call, fail, assert, log, set, wait; conditions
    `decorators`  retry, try/catch, if, unless, for_each
    `params`      `-p` values, binding parameters, the world a plan names
    `validate`    static checks of a parsed plan (`check_plan`) against what is known of its world (`WorldFacts`)
    `language`    registers every node type; `parse_plan`, `load_plan`

The running floor: executing a plan on a world.
    `scheduler`   cancellation tokens and the deterministic turn scheduler of threads
    `trace`       the trace model, JSON (de)serialisation, comparing traces
    `executor`    `run_plan`: `Exec` implements `runtime.Runtime` and runs the nodes

Each node class parses, checks and executes itself (`Node.parse`, `.check`, `.execute(ex, tn)`);
`execute` reaches the run only through `ex` and `tn`.
"""
from .executor import RunResult, run_plan
from .language import NODE_TYPES, Plan, load_plan, parse_plan
from .params import bind_params, parse_assignments, plan_world
from .validate import WorldFacts, check_plan

__all__ = ["NODE_TYPES", "Plan", "RunResult", "WorldFacts", "bind_params", "check_plan", "load_plan",
           "parse_assignments", "parse_plan", "plan_world", "run_plan"]
