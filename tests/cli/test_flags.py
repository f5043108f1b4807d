"""Library errors name settings (`out`, `compare`); the CLI shows each as the option of the running command."""
from __future__ import annotations

import click
import pytest

from pycram_cli.cli.flags import as_options, options_of, with_options
from pycram_cli.cli.options import parse_view
from pycram_cli.errors import InputError, InputErrors, Location, setting
from pycram_cli.sweep.results import record_problem


@click.command()
@click.option("-n", "count", type=int)
@click.option("--out")
@click.option("--replay-count", type=int)
def sweep(count: int, out: str, replay_count: int) -> None:
    """A stand-in with the shapes of options a command has."""


def test_each_option_stands_for_the_setting_it_sets():
    assert options_of(sweep) == {"n": "-n", "out": "--out", "replay_count": "--replay-count"}
    assert options_of(None) == {}


def test_an_error_shows_the_options_in_its_message_suggestion_key_and_place():
    options = options_of(sweep)
    error = InputError(f"{setting('out')} holds a sweep", Location(setting("out")), key=setting("n"),
                       suggestion=f"give another {setting('out')}; {setting('separation')} is no option")
    shown = with_options(InputErrors([error, error]), options)
    assert isinstance(shown, InputErrors)
    first = shown.errors[0]
    assert (first.message, first.location.file, first.key) == ("--out holds a sweep", "--out", "-n")
    assert first.suggestion == "give another --out; `separation` is no option"  # not an option: left as it was
    assert as_options("a file `out` at line 3", {}) == "a file `out` at line 3"


def test_the_library_names_settings_where_it_named_flags():
    problem = record_problem({"index": 0, "seed": 1, "status": "succeeded", "failure": None, "steps": 1,
                              "trace": None, "varied": {}, "timing": {"duration": 0.0, "setup": 0.0},
                              "alternative": "c"}, [{"drop": True}])
    assert problem is not None and "`compare`" in problem and "--" not in problem


def test_the_camera_option_is_read_by_the_cli():
    assert parse_view(None) == "overview" and parse_view("robot") == "robot"
    camera = parse_view("-1.5,-1.5,2.5:1,0.8,0.9")
    assert not isinstance(camera, str) and camera.eye == (-1.5, -1.5, 2.5) and camera.target == (1.0, 0.8, 0.9)
    with pytest.raises(InputError, match="--camera: the camera's eye and target must differ") as bad:
        parse_view("1,1,1:1,1,1")
    assert bad.value.location.file == "--camera"
    with pytest.raises(InputError) as typo:
        parse_view("robt")
    assert typo.value.suggestion == "did you mean 'robot'?"
