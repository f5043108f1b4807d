"""Ctrl-C and SIGTERM (issue 18): the command ends within a second from anywhere — a `wait` alone or inside
`par`, the start-up imports — with exit 130 (143), siblings cancelled and the trace written whole, marked
interrupted. These run `pycram` as a real process (signals need one); each takes about a second."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest

from pycram_cli.plan import load_plan
from pycram_cli.plan.executor import Run
from pycram_cli.plan.trace import load

PYCRAM = [sys.executable, "-c", "from pycram_cli.cli.launch import main; main()"]


def _caught(pid: int) -> int:
    """The mask of signals the process has handlers for (SigCgt in /proc)."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("SigCgt:"):
            return int(line.split()[1], 16)
    return 0


def start(args: list[str], cwd: Path) -> subprocess.Popen:
    return subprocess.Popen([*PYCRAM, *args], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for(predicate, timeout: float = 20.0) -> None:
    deadline = time.monotonic() + timeout
    while not predicate():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.01)


def signal_and_time(process: subprocess.Popen, signum: int) -> tuple[float, str, str]:
    sent = time.monotonic()
    process.send_signal(signum)
    try:
        out, err = process.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        process.kill()  # not left behind spinning when the signal did not end it
        out, err = process.communicate()
        pytest.fail(f"still running 10 s after {signal.Signals(signum).name}:\n{err}")
    return time.monotonic() - sent, out, err


def plan_files(tmp_path: Path, body: str) -> Path:
    (tmp_path / "w.yaml").write_text(textwrap.dedent("""
        objects:
          - {name: floor, type: environment, file: plane.urdf}
          - {name: box, type: box, file: cube_small.urdf, position: [0.5, 0, 0.025]}
    """))
    plan = tmp_path / "p.yaml"
    plan.write_text("world: w.yaml\nbody:\n" + textwrap.indent(textwrap.dedent(body), "  "))
    return plan


def statuses(trace: dict) -> list[str]:
    found = []

    def walk(node: dict) -> None:
        found.append(node["status"])
        for child in node.get("children", []):
            walk(child)

    walk(trace["root"])
    return found


@pytest.mark.parametrize("signum, code, body", [
    (signal.SIGINT, 130, "- log: waiting\n- wait: 60\n- log: never\n"),
    (signal.SIGTERM, 143, "- log: waiting\n- par:\n    - wait: 60\n    - seq: [{wait: 50}, {log: never}]\n"
                          "    - seq: [{log: sibling}, {wait: 40}]\n"),
    # projected runs in this process (the first run is always here) ...
    (signal.SIGINT, 130, "- log: waiting\n- project:\n    alternatives: {slow: [{wait: 60}], quick: [{log: x}]}\n"
                         "    vary: {box: {noise: 0.05}}\n"),
    # ... and on two forked workers (the first run, timed, says the other 19 are worth them)
    (signal.SIGINT, 130, "- log: waiting\n- project:\n    alternatives: {first: [{wait: 0.2}], slow: [{wait: 60}]}\n"
                         "    vary: {box: {noise: 0.05}}\n"),
])
def test_a_signal_during_wait_ends_the_run_within_a_second_with_its_trace(tmp_path, signum, code, body):
    plan = plan_files(tmp_path, body)
    trace = tmp_path / "t.json"
    trace.write_text("the previous trace")
    process = start(["run", str(plan), "--trace", str(trace), "--workers", "2"], tmp_path)
    wait_for(lambda: process.poll() is not None or b"waiting" in _stderr_so_far(process))
    time.sleep(0.3)  # well inside the wait
    workers: list[int] = []
    if "first" in body:  # the workers run the other runs now
        wait_for(lambda: len(children(process.pid)) >= 2)
        workers = children(process.pid)
    took, out, err = signal_and_time(process, signum)
    assert process.returncode == code, err
    assert took < 1.0, f"took {took:.2f} s to end"
    assert "Traceback" not in err
    assert f"interrupted by {signal.Signals(signum).name}" in err
    data = load(trace)  # complete: it passes the trace schema
    assert data["status"] == "interrupted" and data["interrupted"] == {"signal": signal.Signals(signum).name}
    assert not {"pending", "running"} & set(statuses(data)), "the trace is not finished"
    assert "cancelled" in statuses(data)
    if "project" in body:  # the world the trace ends with is the real one, not a projected run's
        assert data["final_state"]["objects"]["box"]["position"] == [0.5, 0.0, 0.025]
    assert not [w for w in workers if Path(f"/proc/{w}").exists()], "worker processes outlived the run"


def children(pid: int) -> list[int]:
    """The processes `pid` started that are still there (Linux)."""
    path = Path(f"/proc/{pid}/task/{pid}/children")
    return [int(c) for c in path.read_text().split()] if path.exists() else []


_buffers: dict[int, bytearray] = {}


def _stderr_so_far(process: subprocess.Popen) -> bytes:
    """What the process wrote to stderr so far (read without blocking)."""
    buffer = _buffers.setdefault(process.pid, bytearray())
    fd = process.stderr.fileno()
    os.set_blocking(fd, False)
    try:
        chunk = os.read(fd, 65536)
        if chunk:
            buffer.extend(chunk)
    except BlockingIOError:
        pass
    return bytes(buffer)


def test_ctrl_c_while_the_modules_load_exits_130_without_a_traceback(tmp_path):
    plan = plan_files(tmp_path, "- log: never\n")
    process = start(["run", str(plan)], tmp_path)
    sigterm = 1 << (signal.SIGTERM - 1)
    wait_for(lambda: _caught(process.pid) & sigterm)  # pycram's handlers are in place; the heavy imports run
    took, out, err = signal_and_time(process, signal.SIGINT)
    assert process.returncode == 130, err
    assert "Traceback" not in err and "never" not in err
    assert took < 1.5


def test_interrupting_a_run_cancels_every_branch_and_marks_the_run(tmp_path, world):
    plan = load_plan(plan_files(tmp_path, """
        - par:
            - wait: 60
            - seq: [{log: a}, {wait: 60}, {log: never}]
            - try_all: [{wait: 60}, {wait: 50}]
    """))
    plan.world = None
    run = Run(plan, world, {})
    result = {}
    thread = threading.Thread(target=lambda: result.update(r=run.execute()))
    before = threading.active_count()
    thread.start()
    time.sleep(0.3)
    started = time.monotonic()
    run.interrupt("SIGINT")
    thread.join(5)
    assert time.monotonic() - started < 1.0
    outcome = result["r"]
    assert outcome.status == "interrupted"
    assert outcome.failure == {"type": "Interrupted", "message": "interrupted by SIGINT", "path": "body"}
    assert outcome.trace["interrupted"] == {"signal": "SIGINT"}
    assert not {"pending", "running"} & set(statuses(outcome.trace))
    assert threading.active_count() == before
    json.dumps(outcome.trace)


def test_ctrl_c_during_an_endless_retry_writes_a_small_trace_within_a_second(tmp_path):
    # the replay record grew one entry per attempt: after a minute the trace could not be written in time
    plan = plan_files(tmp_path, """
        - log: retrying
        - retry: 1000000000
          body: [{log: again}, {fail: PerceptionFailure}]
    """)
    trace = tmp_path / "t.json"
    process = start(["run", str(plan), "--trace", str(trace), "-q"], tmp_path)
    wait_for(lambda: process.poll() is not None or _caught(process.pid) & (1 << (signal.SIGTERM - 1)))
    time.sleep(3.0)  # thousands of attempts
    took, out, err = signal_and_time(process, signal.SIGINT)
    assert process.returncode == 130, err
    assert took < 1.0, f"took {took:.2f} s to end"
    data = load(trace)
    assert data["status"] == "interrupted"
    retry = data["root"]["children"][1]
    assert retry["retries"] > 100
    assert len(data["replay"]["steps"]) < 30 and trace.stat().st_size < 100_000


def test_the_watchdog_says_which_files_were_not_written_when_it_ends_the_process(tmp_path):
    script = textwrap.dedent("""
        import time
        from pycram_cli import interrupts
        interrupts.install()
        interrupts.owe("t.json")
        with interrupts.on_signal(lambda name: None):  # a run that does not stop
            print("ready", flush=True)
            time.sleep(30)
    """)
    process = subprocess.Popen([sys.executable, "-c", script], cwd=tmp_path, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    assert process.stdout.readline().strip() == "ready"
    took, out, err = signal_and_time(process, signal.SIGINT)
    assert process.returncode == 130
    assert 2.5 < took < 5.0
    assert "error: interrupted by SIGINT, and the command did not end within 3 s: exiting now; not written: t.json" \
           in err


def test_ctrl_c_ends_a_large_render_within_a_second(tmp_path):
    # TinyRenderer held the interpreter for the whole 4096x4096 image (about 27 s): no signal handler ran
    plan_files(tmp_path, "- log: x\n")
    process = start(["world", "render", str(tmp_path / "w.yaml"), "-o", str(tmp_path / "big.png"),
                     "--size", "4096x4096"], tmp_path)
    children = Path(f"/proc/{process.pid}/task/{process.pid}/children")
    try:
        wait_for(lambda: process.poll() is not None or children.read_text().strip(), timeout=30)  # rendering
        time.sleep(0.5)
        took, out, err = signal_and_time(process, signal.SIGINT)
    finally:
        if process.poll() is None:
            process.kill()
            process.communicate()
    assert process.returncode == 130, err
    assert took < 1.0, f"took {took:.2f} s to end"
    assert "Traceback" not in err and not (tmp_path / "big.png").exists()
