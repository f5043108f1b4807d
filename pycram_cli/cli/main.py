"""`pycram`: the command-line entry point. Each command group lives in its own module and lists its
commands in `COMMANDS`; they are registered here, explicitly, in the order `pycram --help` shows them."""
from __future__ import annotations

import sys
import warnings
from typing import Any

import click

from .. import interrupts
from ..errors import InputError, InputErrors, PycramError, as_list
from ..world import quiet
from . import console, designators_cmd, query_cmd, run_cmd, trace_cmd, validate_cmd, world_cmd

EXIT_INPUT = 2
EXIT_INTERNAL = 3


class PycramGroup(click.Group):
    """Turns every error into a message and an exit code; never a traceback for bad input."""

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except (InputError, InputErrors) as exc:
            console.input_errors(as_list(exc))
            ctx.exit(EXIT_INPUT)
        except PycramError as exc:
            console.error(str(exc))
            ctx.exit(EXIT_INPUT)
        except (click.exceptions.Exit, click.exceptions.Abort, click.ClickException):
            raise
        except KeyboardInterrupt as exc:
            console.error("interrupted")
            ctx.exit(getattr(exc, "exit_code", None) or interrupts.exit_code() or 130)
        except Exception as exc:  # noqa: BLE001 - last line of defence
            if interrupts.exit_code() is not None:  # a signal interrupted something that reported it otherwise
                console.error("interrupted")
                ctx.exit(interrupts.exit_code())
            if quiet.is_verbose():
                raise
            console.error(f"internal error: {exc.__class__.__name__}: {exc} (run with --verbose for the traceback)")
            ctx.exit(EXIT_INTERNAL)


def _show_warning(message: Any, category: type, filename: str, lineno: int, file: Any = None, line: Any = None) -> None:
    console.warning(str(message))


@click.group(cls=PycramGroup, context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.option("--verbose", is_flag=True, help="Show PyBullet's own console output and full tracebacks.")
@click.version_option(package_name="pycram-cli", prog_name="pycram")
def cli(verbose: bool) -> None:
    """Run robot plans and ask reasoning questions in a lightweight PyBullet world.

    With no world given, commands use the bundled kitchen world.
    """
    quiet.set_verbose(verbose)
    warnings.showwarning = _show_warning


for _command in (*world_cmd.COMMANDS, *validate_cmd.COMMANDS, *query_cmd.COMMANDS, *run_cmd.COMMANDS,
                 *trace_cmd.COMMANDS, *designators_cmd.COMMANDS):
    cli.add_command(_command)


def main() -> None:
    cli(prog_name="pycram")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
