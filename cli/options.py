"""The registration and output options of ``register`` and ``batch``, generated from their one
definition in :mod:`hamta.core.options` (flag, type, default, help), and mapped back generically."""
from __future__ import annotations

import argparse
import re

from ..core.errors import UsageError
from ..core.options import OutputOptions, RegisterOptions, cli_flag, option_fields, option_type

OPTION_CLASSES = (RegisterOptions, OutputOptions)
FLAGS = {f.name: cli_flag(f, spec) for cls in OPTION_CLASSES for f, spec in option_fields(cls)}  # field -> flag


def add_options(parser: argparse.ArgumentParser) -> None:
    """Add one argument per field of :class:`RegisterOptions` and :class:`OutputOptions`."""
    for cls in OPTION_CLASSES:
        for f, spec in option_fields(cls):
            default = f.default
            shown = spec.unset if default is None else default
            kwargs = {"dest": f.name, "help": f"{spec.help} (default: {shown})".replace("%", "%%")}
            kind = option_type(cls, f.name)
            if kind is bool:
                kwargs.update(action="store_true", help=spec.help.replace("%", "%%"))
            elif spec.kind == "list":
                kwargs.update(action="append", default=[], metavar="KEY=VALUE",
                              help=f"{spec.help}; repeatable".replace("%", "%%"))
            elif spec.choice is not None:
                kwargs.update(default=default, metavar="{" + ",".join(spec.choice.values) + "}")
                if not spec.choice.aliases:  # others are checked by the option, which knows the aliases
                    kwargs["choices"] = spec.choice.values
            else:
                kwargs.update(type=kind, default=default, metavar=cli_flag(f, spec)[2:].replace("-", "_").upper())
            parser.add_argument(cli_flag(f, spec), **kwargs)


def settings_from(args: argparse.Namespace):
    """(RegisterOptions, OutputOptions) from the arguments :func:`add_options` added; a bad value's
    message names the flag the user typed, not the field behind it."""
    def build(cls):
        return cls(**{f.name: getattr(args, f.name) for f, _ in option_fields(cls)})
    try:
        return build(RegisterOptions), build(OutputOptions)
    except ValueError as exc:
        raise UsageError(in_flags(str(exc))) from None


def in_flags(message: str) -> str:
    """``message``, which starts with the option's field name (``tolerance_px``), with its flag (``--tolerance``)."""
    return re.sub(r"^[a-z][a-z0-9_]*\b", lambda m: FLAGS.get(m.group(0), m.group(0)), message)
