"""The pytest plugin: a user's own plan gets a golden trace with one fixture call."""
from __future__ import annotations

pytest_plugins = ["pytester"]

PLAN = """\
world: kitchen
body:
  - moving: {target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}
  - looking: {target: [1.3, 0.8, 0.95]}
"""

TEST = """\
def test_my_plan(pycram_golden):
    pycram_golden("my_plan.yaml")
"""


def test_first_run_writes_the_golden_trace_then_runs_compare_and_update_rewrites(pytester):
    pytester.makefile(".yaml", my_plan=PLAN)
    pytester.makepyfile(test_mine=TEST)
    first = pytester.runpytest("-p", "no:cacheprovider")
    first.assert_outcomes(failed=1)
    first.stdout.fnmatch_lines(["*no golden trace yet: wrote*golden/my_plan.trace.json*"])
    assert (pytester.path / "golden" / "my_plan.trace.json").is_file()
    pytester.runpytest("-p", "no:cacheprovider").assert_outcomes(passed=1)

    (pytester.path / "my_plan.yaml").write_text(PLAN.replace("[0.65, 0.7, 0]", "[0.6, 0.7, 0]"))
    changed = pytester.runpytest("-p", "no:cacheprovider")
    changed.assert_outcomes(failed=1)
    changed.stdout.fnmatch_lines(["*no longer behaves as*", "*final_state*", "*--pycram-update-golden*"])
    pytester.runpytest("-p", "no:cacheprovider", "--pycram-update-golden").assert_outcomes(passed=1)
    pytester.runpytest("-p", "no:cacheprovider").assert_outcomes(passed=1)


TEST_GIVEN_TRACE = """\
from pycram_cli.scenario import prepare


def test_my_plan(pycram_golden):
    result = prepare("{plan}").run()
    pycram_golden("my_plan.yaml", trace=result.trace)
"""


def test_a_trace_the_test_recorded_is_compared_instead_of_a_new_run(pytester):
    """`trace=`: the run a test made already is what is compared (the plan named is not run again)."""
    pytester.makefile(".yaml", my_plan=PLAN, other_plan=PLAN.replace("[0.65, 0.7, 0]", "[0.6, 0.7, 0]"))
    pytester.makepyfile(test_mine=TEST)
    pytester.runpytest("-p", "no:cacheprovider").assert_outcomes(failed=1)  # writes the golden trace
    pytester.makepyfile(test_mine=TEST_GIVEN_TRACE.format(plan="my_plan.yaml"))
    pytester.runpytest("-p", "no:cacheprovider").assert_outcomes(passed=1)
    pytester.makepyfile(test_mine=TEST_GIVEN_TRACE.format(plan="other_plan.yaml"))
    other = pytester.runpytest("-p", "no:cacheprovider")
    other.assert_outcomes(failed=1)
    other.stdout.fnmatch_lines(["*my_plan.yaml no longer behaves as*"])
