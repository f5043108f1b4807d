"""Output files are written whole or not at all: readers and concurrent writers never see a part (issue 18)."""
from __future__ import annotations

import json
import threading

import pytest

from pycram_cli.errors import InputError
from pycram_cli.files import read_text, write_atomic
from pycram_cli.plan import trace as traces


def _hammer(target, contents, rounds=300):
    """Writers rewrite `target` with their own content while a reader reads it; what the reader saw."""
    stop = threading.Event()

    def writer(text):
        while not stop.is_set():
            write_atomic(target, text)

    seen = []
    threads = [threading.Thread(target=writer, args=(text,)) for text in contents]
    for thread in threads:
        thread.start()
    try:
        for _ in range(rounds):
            seen.append(target.read_text())
    finally:
        stop.set()
        for thread in threads:
            thread.join()
    return seen


def test_a_reader_sees_the_old_or_the_new_file_never_a_part(tmp_path):
    target = tmp_path / "out.json"
    contents = [json.dumps({"writer": i, "data": str(i) * 300_000}) for i in range(2)]
    write_atomic(target, contents[0])
    seen = _hammer(target, contents)
    assert seen and all(text in contents for text in seen)
    assert target.read_text() in contents
    assert not list(tmp_path.glob(".pycram-*")), "temporary files left behind"


def test_two_runs_saving_the_same_trace_leave_one_of_them_whole(tmp_path):
    target = tmp_path / "trace.json"
    runs = [{"format": traces.FORMAT, "version": traces.VERSION, "plan": f"p{i}.yaml", "status": "succeeded",
             "root": {"path": "body", "type": "seq", "status": "succeeded",
                      "children": [{"path": f"body/{k}:log", "type": "log", "status": "succeeded",
                                    "message": f"run {i}"} for k in range(2000)]}} for i in range(2)]
    texts = [traces.dumps(r) for r in runs]
    traces.save(runs[0], target)
    stop = threading.Event()

    def writer(data):
        while not stop.is_set():
            traces.save(data, target)

    threads = [threading.Thread(target=writer, args=(r,)) for r in runs]
    for thread in threads:
        thread.start()
    try:
        for _ in range(200):
            assert target.read_text() in texts
    finally:
        stop.set()
        for thread in threads:
            thread.join()
    assert traces.load(target)["plan"] in ("p0.yaml", "p1.yaml")


def test_a_failed_write_keeps_the_old_file_and_leaves_no_temporary(tmp_path, monkeypatch):
    target = tmp_path / "keep.txt"
    write_atomic(target, "old")

    def broken(*args):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("os.replace", broken)
    with pytest.raises(InputError, match="cannot write: no space left on the device"):
        write_atomic(target, "new")
    assert target.read_text() == "old"
    assert not list(tmp_path.glob(".pycram-*"))


def test_writing_keeps_the_mode_of_the_file_it_replaces_and_follows_symlinks(tmp_path):
    real = tmp_path / "real.txt"
    write_atomic(real, "one")
    real.chmod(0o640)
    link = tmp_path / "link.txt"
    link.symlink_to(real)
    write_atomic(link, "two")
    assert link.is_symlink() and real.read_text() == "two" and (real.stat().st_mode & 0o777) == 0o640


def test_reading_refuses_what_is_not_a_bounded_regular_file(tmp_path):
    big = tmp_path / "big.txt"
    big.write_text("x" * 100)
    with pytest.raises(InputError, match="too large"):
        read_text(big, 50)
    with pytest.raises(InputError, match="character device"):
        read_text("/dev/zero", 50)
    with pytest.raises(InputError, match="file not found"):
        read_text(tmp_path / "missing.txt", 50)
    with pytest.raises(InputError, match="NUL character"):
        read_text("a\0b", 50)
