"""What to try when a registration did not verify: the options that may help, each with why.

Each front end spells an :class:`Advice` its own way (the CLI as a flag, Processing as the
parameter's label, the HTML report as both), from the same list.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional

RIGID = ("similarity", "linear", "affine")
KEEP_UNVERIFIED = "Keep unverified results"  # the one name of ``accept_unverified`` in every dialog and message


@dataclass(frozen=True)
class Advice:
    """Set ``option`` (a :class:`hamta.core.options.RegisterOptions` field, or ``accept_unverified``,
    an argument of :func:`hamta.core.runner.run`) to ``value`` (True for a flag), because ``why``."""

    option: str
    value: object
    why: str


def advice(result) -> List[Advice]:
    """The options that may help an unverified ``result`` (a :class:`hamta.core.result.RegistrationResult`),
    most specific first; empty for a verified one."""
    v = result.verification
    if v is None or v.verified:
        return []
    options, tips = result.options, []
    if result.plan.mode == "grid":
        held_out = _finite(result.diagnostics["grid"]["held_out_rms_px"])
        return [Advice("tolerance_px", math.ceil(held_out * 10) / 10 if held_out else 5.0,
                       "the sheet's printed grid is followed only this well (its paper, its drawing): ask for that "
                       "accuracy, in scan px, if it is enough"),
                Advice("model", "tps", "a sheet whose paper is warped or folded may need a thin plate spline, "
                       "held out line by line like the others"),
                Advice("accept_unverified", True, "to write the outputs anyway, marked NOT VERIFIED, once the "
                       "report's overlays look right")]
    if result.plan.mode == "georeferenced":
        tips.append(Advice("target_georef", "ignore", "the target's own georeferencing, the starting point, may be "
                           "too far off"))
    if result.plan.mode == "search":
        tips.append(Advice("extent", "xmin,ymin,xmax,ymax", "a search area a few times the target's size, around "
                           "where it is (in QGIS: the map zoomed closer to it), finds it more often; a target that "
                           "is mirrored, or whose ground has mostly changed since, may not be found at all"))
    bound = _finite(v.error_bound_px)
    if bound is not None and bound > v.tolerance_px and (_finite(v.error_px) or math.inf) <= v.tolerance_px:
        tips.append(Advice("tolerance_px", math.ceil(bound * 10) / 10, "the estimated error is within the accuracy "
                           "asked for but its bound is not: ask for that accuracy if it is enough"))
    if options.get("model") in RIGID:
        tips.append(Advice("model", "polynomial-2", f"the {options['model']} model may not follow the target's "
                           "distortion (a scanned sheet, terrain, a large footprint)"))
    if not options.get("local"):
        tips.append(Advice("local", True, "local misalignment may exceed what one model follows"))
    tips.append(Advice("accept_unverified", True, "to write the outputs anyway, marked NOT VERIFIED, once the "
                       "report's overlays look right"))
    return tips


def spelled(tip: Advice) -> str:
    """``tip`` as the command line sets it (``--local``, ``--model polynomial-2``) with the dialogs' label."""
    from .options import RegisterOptions, cli_flag, option_fields

    specs = {f.name: (cli_flag(f, spec), spec.label) for f, spec in option_fields(RegisterOptions)}
    flag, label = specs.get(tip.option, ("--" + tip.option.replace("_", "-"), KEEP_UNVERIFIED))
    return f"{flag}{'' if tip.value is True else f' {tip.value}'} (QGIS: '{label}')"


def _finite(value) -> Optional[float]:
    return None if value is None or not math.isfinite(value) else float(value)
