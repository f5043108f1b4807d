"""Library errors name the settings and parameters they are about (`out`, `from`: see `errors.setting`); a CLI
user set them with options. This module shows each as the option of the running command that sets it (`--out`,
`-n`), in the message, the suggestion and the place of an error, so that what the CLI prints names what to type.
"""
from __future__ import annotations

import dataclasses
import re
from collections.abc import Mapping

import click

from ..errors import InputError, InputErrors, Location, PycramError

_NAMED = re.compile(r"`([a-z][a-z0-9_]*)`")


def options_of(command: click.Command | None) -> dict[str, str]:
    """Every option of a command (and of a group's subcommands) by the setting it stands for: `out` -> `--out`,
    `n` -> `-n`, `replay_count` -> `--replay-count` (a long option wins over a short one)."""
    found: dict[str, str] = {}
    commands = [command] if command is not None else []
    if isinstance(command, click.Group):
        commands += list(command.commands.values())
    for each in commands:
        for param in each.params:
            for option in sorted(getattr(param, "opts", ()), key=len, reverse=True):
                if option.startswith("-"):
                    found.setdefault(option.lstrip("-").replace("-", "_"), option)
    return found


def as_options(text: str, options: Mapping[str, str]) -> str:
    """`text` with each setting it names (in backticks) shown as its option, when the command has one."""
    return _NAMED.sub(lambda m: options.get(m.group(1), m.group(0)), text)


def with_options(error: PycramError, options: Mapping[str, str]) -> PycramError:
    """The same error as the CLI shows it: its settings named by the options that set them."""
    if isinstance(error, InputErrors):
        return InputErrors([_input_error(e, options) for e in error.errors])
    if isinstance(error, InputError):
        return _input_error(error, options)
    return error


def _input_error(error: InputError, options: Mapping[str, str]) -> InputError:
    place = error.location
    if place.file is not None and place.line is None:
        place = Location(as_options(place.file, options), place.line, place.column)
    return dataclasses.replace(error, message=as_options(error.message, options), location=place,
                               key=as_options(error.key, options) if error.key else error.key,
                               suggestion=as_options(error.suggestion, options) if error.suggestion else None)
