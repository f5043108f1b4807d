"""`pycram`: the command-line entry point.

Each command group lives in its own module and is registered here, explicitly, in `COMMANDS`
(in the order `pycram --help` shows them). A command's module is imported only when that
command runs, so `pycram --help` and light commands start without loading PyBullet.
"""
from __future__ import annotations

import importlib
import sys
import traceback
import warnings
from typing import Any

import click

from .. import interrupts, quiet
from ..errors import InputError, InputErrors, PycramError, as_list
from ..failures import InternalError
from . import console
from .flags import as_options, options_of, with_options

EXIT_INPUT = 2
EXIT_INTERNAL = 3  # a bug in pycram (an internal error): said in one line, with where to report it
BUGS = "on the issue tracker of pycram-cli's repository"


#: every command: name -> (its module in pycram_cli.cli, the click command's name there, its one-line help)
COMMANDS: dict[str, tuple[str, str, str]] = {
    "run": ("run_cmd", "run", "Validate and run PLAN (a plan file, or the name of a bundled plan)."),
    "sweep": ("sweep_cmd", "sweep",
              "Run PLAN over many scenarios varied as VARY.yaml says, in parallel; summarise where it fails."),
    "validate": ("validate_cmd", "validate",
                 "Check world, plan and variation FILES (or bundled names) as `run` and `sweep` would; report every "
                 "problem with file, line and key."),
    "plans": ("plans_cmd", "plans",
              "List the plans: the working folder's plans/ first, then the bundled ones, with descriptions and parameters."),
    "worlds": ("worlds_cmd", "worlds",
               "List the worlds: the working folder's worlds/ first, then the bundled ones, with their robot and objects."),
    "new": ("new_cmd", "new", "Write a starting file: a commented plan, a world made from another, variations for sweeps."),
    "query": ("query_cmd", "query", "Ask a reasoning question (stable, visible, reachable, ...) about a world."),
    "locate": ("locate_cmd", "locate_cmd", "Resolve a location designator: where to stand, or a free spot on a surface."),
    "world": ("world_cmd", "world", "Inspect and render world files."),
    "designators": ("designators_cmd", "designators",
                    "List every motion designator and action designator with its slots (or just TYPE)."),
    "trace": ("trace_cmd", "trace", "Show saved plan traces and compare them."),
    "schema": ("schema_cmd", "schema",
               "Print the JSON Schema of world, plan or variation files, for editors (completion, checks as you "
               "type)."),
}

#: options of the whole program that may also be written after the command (`pycram run x --verbose`)
GLOBAL_FLAGS = ("--verbose", "-q", "--quiet")


class PycramGroup(click.Group):
    """Turns every error into a message and an exit code; never a traceback for bad input.

    With `--json`, input errors are also given as a JSON object on stdout, so that a program
    reading stdout always gets JSON.
    """

    def list_commands(self, ctx: click.Context) -> list[str]:
        return list(COMMANDS)

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        entry = COMMANDS.get(name)
        if entry is None:
            return None
        module = importlib.import_module(f"{__package__}.{entry[0]}")  # why: load a command only when it runs
        command = getattr(module, entry[1])
        assert isinstance(command, click.Command)
        return command

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """The command list from the table, without importing every command's module."""
        with formatter.section("Commands"):
            formatter.write_dl([(name, help_text) for name, (_, _, help_text) in COMMANDS.items()])

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        head, sep, tail = (args[: args.index("--")], ["--"], args[args.index("--") + 1:]) if "--" in args else (args, [], [])
        flags = [a for a in head if a in GLOBAL_FLAGS]
        ctx.meta["pycram.json"] = "--json" in head
        return super().parse_args(ctx, flags + [a for a in head if a not in GLOBAL_FLAGS] + sep + tail)

    def _options(self, ctx: click.Context) -> dict[str, str]:
        """The options of the command that ran, by the settings library errors name (cli/flags.py)."""
        name = ctx.invoked_subcommand
        return options_of(self.get_command(ctx, name) if name else None)

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except (InputError, InputErrors) as exc:
            problems = as_list(with_options(exc, self._options(ctx)))
            console.input_errors(problems)
            if ctx.meta.get("pycram.json"):
                console.emit_json({"status": "error", "exit_code": EXIT_INPUT, "errors": [p.to_json() for p in problems]})
            ctx.exit(EXIT_INPUT)
        except PycramError as exc:
            console.error(as_options(str(exc), self._options(ctx)))
            if ctx.meta.get("pycram.json"):
                console.emit_json({"status": "error", "exit_code": EXIT_INPUT, "errors": [{"message": str(exc)}]})
            ctx.exit(EXIT_INPUT)
        except (click.exceptions.Exit, click.exceptions.Abort, click.ClickException):
            raise
        except KeyboardInterrupt as exc:
            console.error("interrupted")
            ctx.exit(getattr(exc, "exit_code", None) or interrupts.exit_code() or 130)
        except Exception as exc:  # last line of defence
            if interrupts.exit_code() is not None:  # a signal interrupted something that reported it otherwise
                console.error("interrupted")
                ctx.exit(interrupts.exit_code() or 130)
            if quiet.is_verbose():
                traceback.print_exception(exc, file=sys.stderr)
            console.error(internal_error_line(exc, quiet.is_verbose()))
            if ctx.meta.get("pycram.json"):
                console.emit_json({"status": "error", "exit_code": EXIT_INTERNAL, "errors": [{"message": str(exc)}]})
            ctx.exit(EXIT_INTERNAL)


def internal_error_line(exc: BaseException, verbose: bool) -> str:
    """The one line an internal error gets: what was raised (and at which step), that it is a bug, and where to
    report it."""
    what = str(exc) if isinstance(exc, InternalError) else f"{type(exc).__name__}: {exc}"
    how = "with the traceback above" if verbose else "with the output of the same command run with --verbose"
    return f"internal error: {what}. This is a bug in pycram, not in your files: please report it {how} {BUGS}"


def _show_warning(message: Any, category: type, filename: str, lineno: int, file: Any = None, line: Any = None) -> None:
    console.warning(str(message))


@click.group(cls=PycramGroup, context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.option("--verbose", is_flag=True, help="Show PyBullet's own console output and full tracebacks (anywhere on the line).")
@click.option("-q", "--quiet", "be_quiet", is_flag=True, help="Only results and errors: no progress, no info lines.")
@click.version_option(package_name="pycram-cli", prog_name="pycram")
def cli(verbose: bool, be_quiet: bool) -> None:
    """Run robot plans and ask reasoning questions in a lightweight PyBullet world.

    With no world given, commands use the bundled kitchen world.
    """
    quiet.set_verbose(verbose)
    console.set_quiet(be_quiet)
    warnings.showwarning = _show_warning


def main() -> None:
    cli(prog_name="pycram")


if __name__ == "__main__":  # pragma: no cover
    main()
