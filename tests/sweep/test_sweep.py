"""`pycram sweep` from a user's point of view: results.jsonl, determinism across worker counts and
backends, resume, timeouts and crashes recorded, --compare, --json, --plot, and replaying one
scenario alone with `pycram run --scenario`."""
from __future__ import annotations

import importlib.util
import json
import sys
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.designators import DESIGNATORS
from pycram_cli.paths import plans_dir
from pycram_cli.process_modules import PROCESS_MODULES
from pycram_cli.reasoning import QUERIES
from pycram_cli.scenario.variations import scenario_seed
from pycram_cli.sweep import local
from pycram_cli.sweep.worker import SweepJob, Task, Worker, trace_digest

FAULTY = Path(__file__).resolve().parents[1] / "data" / "extension" / "faulty.py"


def run(*args: str):
    return CliRunner().invoke(cli, [str(a) for a in args])


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(textwrap.dedent(text))
    return path


@pytest.fixture
def small(tmp_path: Path) -> Path:
    """A box on the floor: it stays put when put down low enough, and falls (unstable) otherwise."""
    write(tmp_path, "small.yaml", """\
        objects:
          - {name: floor, type: environment, file: plane.urdf}
          - {name: box, type: box, file: cube_small.urdf, position: [0.5, 0, 0.025]}
          - {name: other, type: box, file: cube_small.urdf, position: [0, 0.5, 0.025]}
    """)
    write(tmp_path, "drop.yaml", """\
        world: small.yaml
        params: {drop: false, wait: 0}
        body:
          - if: $drop
            then: [{fail: ManipulationFailure, message: "dropped the box"}]
          - wait: $wait
          - assert: {stable: {object: box}}
            message: "the box moves"
    """)
    write(tmp_path, "drop.vary.yaml", """\
        objects:
          box: {region: {box: [[0, -0.5, 0.025], [1, 0.5, 0.03]]}}
          other: {present: 0.5}
    """)
    return tmp_path


def records(folder: Path) -> list[dict]:
    return [json.loads(line) for line in (folder / "results.jsonl").read_text().splitlines()]


def untimed(folder: Path) -> list[dict]:
    return [{k: v for k, v in r.items() if k != "timing"} for r in records(folder)]


def sweep(small: Path, out: str, *args: str):
    return run("sweep", small / "drop.yaml", "--out", small / out, *args)


def test_results_are_the_same_whatever_the_number_of_workers(small):
    one = sweep(small, "one", "-n", "8", "--workers", "1", "--seed", "7")
    two = sweep(small, "two", "-n", "8", "--workers", "2", "--seed", "7")
    assert one.exit_code == 0, one.output
    assert two.exit_code == 0, two.output
    assert untimed(small / "one") == untimed(small / "two")
    found = records(small / "two")
    assert [r["index"] for r in found] == list(range(8))
    assert {r["status"] for r in found} == {"succeeded", "failed"}  # the sample shows both outcomes
    first = found[0]
    assert set(first) == {"index", "seed", "status", "failure", "steps", "trace", "varied", "timing"}
    assert set(first["varied"]) == {"box", "other"} and len(first["varied"]["box"]["position"]) == 3
    assert set(first["timing"]) == {"duration", "setup"}
    failed = next(r for r in found if r["status"] == "failed")
    assert failed["failure"]["type"] == "ReasoningFailure" and failed["failure"]["path"] == "body/2:assert"
    meta = json.loads((small / "two" / "sweep.json").read_text())
    assert meta["seed"] == 7 and meta["n"] == 8 and meta["vary"].endswith("drop.vary.yaml")
    assert "succeeded" in two.stdout and "95 % interval" in two.stdout and "ReasoningFailure at body/2:assert" in two.stdout
    other = sweep(small, "other", "-n", "8", "--workers", "2", "--seed", "8")
    assert untimed(small / "other") != untimed(small / "two")


def test_json_summary(small):
    result = sweep(small, "out", "-n", "6", "--workers", "2", "--json")
    assert result.exit_code == 0, result.output
    summary = json.loads(result.stdout)  # nothing else on stdout
    assert summary["runs"] == summary["scenarios"] == 6 and summary["complete"] is True
    ok = summary["succeeded"]
    assert summary["rate"] == round(ok / 6, 4)
    lo, hi = summary["interval"]
    assert 0 <= lo <= ok / 6 <= hi <= 1
    assert sum(f["count"] for f in summary["failures"]) == 6 - ok
    for failure in summary["failures"]:
        assert failure["example"]["replay"].startswith("pycram run ")
        assert f"--scenario {failure['example']['seed']}" in failure["example"]["replay"]
    assert summary["time"]["median"] > 0 and summary["throughput"]["runs"] == 6


def test_resume_runs_only_what_is_missing_and_checks_it_is_the_same_sweep(small):
    first = sweep(small, "out", "-n", "3", "--workers", "1")
    assert first.exit_code == 0, first.output
    again = sweep(small, "out", "-n", "3")
    assert again.exit_code == 2 and "holds the results of a sweep already" in again.stderr
    assert "--resume" in again.stderr
    path = small / "out" / "results.jsonl"
    path.write_text(path.read_text() + '{"index": 3, "seed": 1, "stat')  # torn by an interruption
    more = sweep(small, "out", "-n", "5", "--workers", "1", "--resume", "--json")
    assert more.exit_code == 0, more.output
    summary = json.loads(more.stdout)
    assert summary["throughput"]["runs"] == 2 and summary["runs"] == 5
    assert [r["index"] for r in records(small / "out")] == [0, 1, 2, 3, 4]
    whole = sweep(small, "whole", "-n", "5", "--workers", "1")
    assert whole.exit_code == 0
    assert untimed(small / "whole") == untimed(small / "out")
    other = sweep(small, "out", "-n", "5", "--seed", "3", "--resume")
    assert other.exit_code == 2 and "differs from the one in" in other.stderr and "seed" in other.stderr


def test_the_same_sweep_again_is_refused_naming_resume_and_force_and_force_runs_it_again(small):
    assert sweep(small, "out", "-n", "2", "--workers", "1").exit_code == 0
    before = untimed(small / "out")
    again = sweep(small, "out", "-n", "2", "--workers", "1")
    assert again.exit_code == 2 and "add --resume to go on with it, --force to run it again" in again.stderr
    forced = sweep(small, "out", "-n", "3", "--workers", "1", "--seed", "0", "--force", "--json")
    assert forced.exit_code == 0, forced.output
    assert json.loads(forced.stdout)["throughput"]["runs"] == 3  # from the start, not resumed
    assert untimed(small / "out")[:2] == before and len(records(small / "out")) == 3
    both = sweep(small, "out", "-n", "3", "--force", "--resume")
    assert both.exit_code == 2 and "--force starts the sweep again and --resume goes on with it" in both.stderr


def test_without_a_variation_file_the_error_says_how_to_write_one(small):
    (small / "drop.vary.yaml").unlink()
    result = sweep(small, "out", "-n", "2")
    assert result.exit_code == 2
    assert "a sweep needs a variation file, and none named drop.vary.yaml is beside the plan: give --vary FILE" \
        in result.stderr and "`pycram new vary drop` writes plans/drop.vary.yaml" in result.stderr
    assert "((" not in result.stderr and "))" not in result.stderr


def test_a_scenario_past_the_timeout_is_recorded_and_the_sweep_goes_on(small):
    vary = write(small, "slow.vary.yaml", """\
        params:
          wait: [0, 30]
    """)
    result = sweep(small, "out", "--vary", vary, "-n", "6", "--workers", "2", "--timeout", "1.5", "--json")
    assert result.exit_code == 0, result.output
    found = records(small / "out")
    assert len(found) == 6
    slow = [r for r in found if r["varied"]["params"]["wait"] == 30]
    quick = [r for r in found if r["varied"]["params"]["wait"] == 0]
    assert slow and quick
    assert all(r["status"] == "timeout" and r["failure"]["type"] == "Timeout" for r in slow)
    assert all(r["status"] in ("succeeded", "failed") for r in quick)
    assert json.loads(result.stdout)["statuses"]["timeout"] == len(slow)


@pytest.fixture
def faulty():
    saved = dict(QUERIES), dict(DESIGNATORS), dict(PROCESS_MODULES)
    spec = importlib.util.spec_from_file_location("pycram_extension_faulty", FAULTY)
    module = importlib.util.module_from_spec(spec)
    sys.modules["pycram_extension_faulty"] = module
    spec.loader.exec_module(module)
    yield str(FAULTY)
    del sys.modules["pycram_extension_faulty"]
    for registry, before in zip((QUERIES, DESIGNATORS, PROCESS_MODULES), saved):
        registry.clear()
        registry.update(before)


def test_internal_errors_crashes_and_hung_workers_are_recorded(small, faulty, monkeypatch):
    from pycram_cli.sweep import SweepSettings, prepare_sweep, run_sweep

    write(small, "faulty.yaml", """\
        world: small.yaml
        params: {how: fine}
        body:
          - if: {equal: [$how, explode]}
            then: [{explode: {}}]
          - if: {equal: [$how, crash]}
            then: [{crash: {}}]
          - if: {equal: [$how, spin]}
            then: [{par: [{spin: {}}, {log: "spinning"}]}]
          - if: {equal: [$how, hang]}
            then: [{block: {}}]
          - log: "$how"
    """)
    vary = write(small, "faulty.vary.yaml", """\
        params:
          how: [fine, explode, crash, spin, hang]
    """)
    monkeypatch.setattr(local, "GRACE", 0.5)
    settings = SweepSettings(str(small / "faulty.yaml"), str(vary), n=10, seed=7, workers=2, out=small / "out", timeout=1.0,
                             imports=(faulty,))
    summary = run_sweep(prepare_sweep(settings))
    found = records(small / "out")
    assert [r["index"] for r in found] == list(range(10))
    by_how = {}
    for record in found:
        by_how.setdefault(record["varied"]["params"]["how"], set()).add((record["status"],
                                                                        (record["failure"] or {}).get("type")))
    assert by_how["fine"] == {("succeeded", None)}
    assert by_how["explode"] == {("error", "InternalError")}
    assert by_how["crash"] == {("error", "InternalError")}
    assert by_how["hang"] == by_how["spin"] == {("timeout", "Timeout")}
    messages = {r["varied"]["params"]["how"]: r["failure"]["message"] for r in found if r["failure"]}
    assert "RuntimeError: boom" in messages["explode"]
    assert "the worker process died (exit code 3)" in messages["crash"]
    assert "the worker was stopped" in messages["hang"]  # killed: it could not interrupt the step itself
    # interrupted by the worker, which then retired (on a loaded machine the worker may have to be stopped instead)
    assert messages["spin"].startswith("ran past the 1 s timeout")
    assert summary["runs"] == 10


def test_compare_runs_every_scenario_once_per_alternative(small):
    result = sweep(small, "out", "-n", "4", "--workers", "2", "--compare", "drop=false,true", "--json")
    assert result.exit_code == 0, result.output
    found = records(small / "out")
    assert [(r["index"], r["alternative"]) for r in found] == [
        (i, {"drop": d}) for i in range(4) for d in (False, True)]
    compare = json.loads(result.stdout)["compare"]
    assert compare["param"] == "drop" and compare["best"] is False
    assert [row["value"] for row in compare["alternatives"]] == [False, True]
    assert compare["alternatives"][1]["rate"] == 0.0
    succeeded = {r["index"] for r in found if r["status"] == "succeeded"}
    assert succeeded and [row["index"] for row in compare["differ"]] == [0, 1, 2, 3]  # ManipulationFailure vs the rest
    text = sweep(small, "text", "-n", "4", "--compare", "drop=false,true")
    assert "best: drop=False" in text.stdout and "differ on" in text.stdout
    bad = sweep(small, "bad", "-n", "4", "--compare", "dorp=false,true")
    assert bad.exit_code == 2 and "--compare: dorp:" in bad.stderr and "did you mean 'drop'" in bad.stderr


def test_plot_draws_a_map_of_the_outcomes(small):
    result = sweep(small, "out", "-n", "6", "--workers", "2", "--plot", small / "map.png")
    assert result.exit_code == 0, result.output
    data = (small / "map.png").read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and int.from_bytes(data[16:20], "big") == 960


def test_ray_backend_agrees_with_the_local_one(small):
    pytest.importorskip("ray", reason="Ray is not installed (pip install '.[ray]'): the ray backend is not tested")
    result = sweep(small, "ray", "-n", "6", "--workers", "2", "--backend", "ray")
    assert result.exit_code == 0, result.output
    assert sweep(small, "local", "-n", "6", "--workers", "2").exit_code == 0
    assert untimed(small / "ray") == untimed(small / "local")


def test_the_ray_backend_says_how_to_install_ray_when_it_is_missing(small, monkeypatch):
    monkeypatch.setitem(sys.modules, "ray", None)  # import ray fails
    result = sweep(small, "out", "-n", "2", "--backend", "ray")
    assert result.exit_code == 2
    assert "pip install 'pycram-cli[ray]'" in result.stderr


def test_address_needs_the_ray_backend_and_a_cluster_that_answers(small, monkeypatch):
    result = sweep(small, "out", "-n", "2", "--address", "auto")  # was silently ignored on the local backend
    assert result.exit_code == 2 and "--address: joins a Ray cluster: it needs --backend ray" in result.stderr
    for address, message in (("127.0.0.1:1", "cannot join a Ray cluster at '127.0.0.1:1': nothing answers there"),
                             ("nonsense", "expected HOST:PORT (or ray://HOST:PORT, or auto), got 'nonsense'")):
        result = sweep(small, "out", "-n", "2", "--backend", "ray", "--address", address)
        assert result.exit_code == 2 and f"--address: {message}" in result.stderr, result.output
        assert "ray start --head" in result.stderr and not (small / "out").exists()

    class NoCluster:  # what Ray does for `--address auto` when no cluster runs: a ConnectionError (was exit 3)
        @staticmethod
        def is_initialized() -> bool:
            return False

        @staticmethod
        def init(**options) -> None:
            raise ConnectionError("Could not find any running Ray instance.")

    monkeypatch.setattr("pycram_cli.sweep.ray_backend.load_ray", lambda: NoCluster)
    result = sweep(small, "out", "-n", "2", "--backend", "ray", "--address", "auto")
    assert result.exit_code == 2, result.output
    assert "--address: cannot join a Ray cluster at 'auto': Could not find any running Ray instance." in result.stderr
    assert "ray start --head" in result.stderr


def test_results_are_written_through_a_temporary_file_of_their_own(small):
    # a fixed `sweep.json.tmp` / `results.jsonl.tmp`: two sweeps on the same --out could take each other's
    (small / "out").mkdir()
    for name in ("sweep.json.tmp", "results.jsonl.tmp"):
        (small / "out" / name).mkdir()  # in the way of a fixed temporary name
    result = sweep(small, "out", "-n", "2", "--workers", "1")
    assert result.exit_code == 0, result.output
    assert len(records(small / "out")) == 2 and json.loads((small / "out" / "sweep.json").read_text())["n"] == 2


def test_a_sweep_of_the_set_table_demo_and_one_scenario_replayed_alone(tmp_path):
    result = run("sweep", "set_table", "-n", "3", "--workers", "2", "--out", tmp_path / "out", "--json")
    assert result.exit_code == 0, result.output
    summary = json.loads(result.stdout)
    assert summary["vary"].endswith("plans/set_table.vary.yaml") and summary["runs"] == 3
    found = records(tmp_path / "out")
    for record in found[:2]:
        replay = run("run", "set_table", "--scenario", record["seed"], "--json")
        data = json.loads(replay.stdout)
        assert data["status"] == record["status"] and replay.exit_code == (0 if data["status"] == "succeeded" else 1)
        assert trace_digest(data["trace"]) == record["trace"]  # the very same run, step for step


@pytest.mark.parametrize("values, message", [
    ("[" * 10_000 + "]" * 10_000 + ",1", "nested deeper than"),
    ("&a [1,1,1,1,1,1,1,1,1,1], " + ", ".join(f"&{b} [{', '.join([f'*{a}'] * 10)}]" for a, b in zip("abcde", "bcdef"))
     + ", *f", "values"),
])
def test_compare_values_are_read_with_the_limits_of_every_yaml_value(small, values, message):
    result = sweep(small, "out", "-n", "2", "--compare", f"wait={values}")
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output and "internal error" not in result.stderr
    assert "--compare" in result.stderr
    if message:
        assert message in result.stderr


def test_a_ray_cluster_lost_after_connecting_ends_the_sweep_with_a_clear_error(monkeypatch):
    """Ray's own wait for a result has no bound: a cluster that drops once scenarios run would hang the sweep. The
    backend checks every HEARTBEAT that a node is alive and ends with an error naming the address."""
    from pycram_cli.sweep import ray_backend
    from pycram_cli.sweep.local import SweepError

    class Lost:  # connected, actors started, then the cluster is gone: nothing ever finishes and nodes() fails
        @staticmethod
        def is_initialized() -> bool:
            return True

        @staticmethod
        def remote(**options):
            class Handle:
                def __init__(self, *args):
                    self.ready = self.run = type("M", (), {"remote": staticmethod(lambda *a: object())})

                @classmethod
                def remote(cls, *args):
                    return cls()
            return lambda worker_class: Handle

        @staticmethod
        def get(refs, timeout=None):
            return refs

        @staticmethod
        def wait(refs, num_returns=1, timeout=None):
            assert timeout is not None and timeout <= ray_backend.HEARTBEAT  # never an unbounded wait
            return [], refs

        @staticmethod
        def nodes():
            raise ConnectionError("GCS lost")

    monkeypatch.setattr(ray_backend, "load_ray", lambda: Lost)
    monkeypatch.setattr(ray_backend, "HEARTBEAT", 0.01)
    with pytest.raises(SweepError, match="lost the Ray cluster at '10.0.0.1:6379' while 2 scenario"):
        job = type("Job", (), {"timeout": None})()  # no --timeout: before, the wait had no bound at all
        ray_backend.run(job, [object(), object(), object()], 2, lambda outcome: None, address="10.0.0.1:6379")


def test_a_scenario_on_a_worker_that_ran_others_gives_the_trace_it_gives_alone():
    """A worker keeps its world loaded and resets it for each scenario: the demo's scenario 3, run after 0-2, gives
    byte for byte the trace it gives on a fresh worker. Before, its placed objects settled a few micrometres
    elsewhere (contacts and warm starts the earlier runs left in PyBullet) and IK answered from an earlier run's
    answers kept within a rounding, so a sweep's results depended on how many workers shared it."""
    job = SweepJob(str(plans_dir() / "set_table.yaml"), str(plans_dir() / "set_table.vary.yaml"))
    used = Worker(job)
    for index in range(3):
        used.run(Task(index, scenario_seed(0, index)))
    after = used.run(Task(3, scenario_seed(0, 3)))
    alone = Worker(job).run(Task(3, scenario_seed(0, 3)))
    assert after["status"] == alone["status"] == "succeeded"
    assert after["trace"] == alone["trace"]
