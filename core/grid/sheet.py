"""A scanned sheet's printed crossings, found from a few hints (two or three crossings with their coordinates,
placed roughly by a person or made of the labels printed in the margins).

From the hints: the grid's step (the largest usual step every hint's coordinates are multiples of, or the one
given, :mod:`hamta.core.grid.steps`) and, in each plane the sheet may be drawn in (:mod:`hamta.core.grid.planes`),
a first model (a similarity from two hints, an affine from three). The lattice of every grid line is placed on
the scan from it (:mod:`hamta.core.grid.lattice`) and judged against the sheet's own background; the plane whose
lattice the scan holds surest is kept, at the largest step whose lines are printed. Each crossing is then found
where it is printed (:func:`hamta.core.grid.lines.crossing`, sub-pixel), the model refitted on what was found and
the crossings looked for again, closer. What the crossings are worth (the model, the verdict) is judged once, by
:mod:`hamta.core.grid.check`.

Coordinates: scan pixels (corner convention); grid coordinates in the sheet's CRS (what the printed labels
count in: degrees of a graticule, or a national grid's metres, feet or yards); plane coordinates (metres of
the plane).
"""
from __future__ import annotations

import math
from typing import List, Optional, Sequence

import numpy as np

from ..errors import InputError
from ..estimation.models import LinearModel
from .crossings import ordered, to_scan
from .evidence import CHANCE
from .finding import SheetFit, find_crossings
from .placing import MAX_CROSSINGS, MIN_STEP_PX, Attempt, Placed, few_lines, first_model, place_lattice, too_fine
from .planes import Plane, planes_for
from .scan import LineSource
from .steps import describe_pair, hint_steps

HINT_PX = 0.15  # of the grid's spacing: how far from a crossing a hint may be placed
STEPS_SPAN = 1e6  # the steps the hints fit that are tried: all, largest first, until their crossings are too close
# (hints on one line leave its step open)
class NoGridFound(InputError):
    """No lattice of the hints' steps is printed where they put it, in any plane tried; ``tried`` lists what was
    (plane, step, evidence), for the report."""

    def __init__(self, message: str, tried, geographic: bool):
        super().__init__(message)
        self.tried, self.geographic = list(tried), geographic


def fit_sheet(scan, hints: Sequence, sheet_crs, steps=None, drawn_in=None, progress=None,
              placed_by_hand: bool = True) -> SheetFit:
    """Find the sheet's printed crossings from ``hints`` (rows of scan x, y, grid x, y in ``sheet_crs``, a pyproj
    CRS); ``steps``: the grid's steps to try along grid x and along grid y (two lists, largest first; None: those
    the hints' coordinates fit); ``drawn_in``: a projected CRS the user says the sheet is drawn in (tried first).
    ``scan``: a :class:`LineSource`, or the scan as a grey 2-D array. Raises :class:`NoGridFound` where no lattice
    of the hints' steps is printed, and :class:`InputError` for hints the printed lattice contradicts (naming the
    hint placed by hand; ``placed_by_hand`` False: hints made of labels, which the check holds to the lattice
    itself). ``progress``: a :class:`hamta.core.progress.Monitor` (reports, and raises where the user cancelled)."""
    from ..progress import Monitor

    monitor = progress or Monitor(None, None)
    hints = np.asarray(hints, float).reshape(-1, 4)
    if len(hints) < 2:
        raise InputError("Georeferencing by the grid needs at least two crossings placed with their coordinates "
                         f"(got {len(hints)}).")
    geographic = sheet_crs.is_geographic
    steps = [list(s) for s in steps] if steps else [hint_steps(hints[:, 2 + a], geographic, STEPS_SPAN)
                                                     for a in (0, 1)]
    source = scan if isinstance(scan, LineSource) else LineSource.from_array(scan)
    planes = ([Plane("the CRS given", drawn_in, sheet_crs)] if drawn_in is not None else []) + \
        planes_for(sheet_crs, _lon_lat_box(hints, source.shape) if geographic else None)
    monitor.report(0.0, "grid: the lattice")
    works, tried, best = {}, [], None
    for k, plane in enumerate(planes):  # the largest steps the hints allow whose lines are printed, each family's
        # smaller where its lines are not; in the other planes, those steps: the plane whose affine lattice lies on
        # most of the printed lines is kept
        monitor.report(0.6 * k / len(planes), f"grid: the lattice in {plane.name}")
        found = _printed(source, works, plane, hints, steps if best is None else [[s] for s in best[1].step],
                         tried, geographic, CHANCE)
        if found is not None and (best is None or found.lattice.straight > best[1].lattice.straight):
            best = (plane, found)
    if best is None:
        raise NoGridFound(_not_found(tried, geographic, placed_by_hand), tried, geographic)
    best = (best[0], place_lattice(source, works, best[0], hints, best[1].step, bend=True,
                              threshold=best[1].evidence.threshold) or best[1])
    plane, lat = best
    monitor.report(0.6, "grid: each crossing")
    fit = find_crossings(source, plane, lat, monitor)
    fit.tried = tried
    if placed_by_hand:
        _check_hints(hints, plane.forward(hints[:, 2:]), to_scan(fit.crossings, fit.order)
                     if len(fit.crossings) >= 6 else lat.lattice.model, lat.spacing)
    lines = [len(np.unique(fit.crossings[:, 4 + a])) for a in (0, 1)]
    if len(fit.crossings) < 3 or min(lines) < 2:
        raise NoGridFound(f"Only {len(fit.crossings)} crossings of the printed grid were found ({lines[0]} and "
                          f"{lines[1]} lines each way), on the lattice of {describe_pair(lat.step, geographic)} in "
                          f"{plane.name} ({lat.evidence.text()}): too few to place the sheet.", tried, geographic)
    if len(planes) > 1:
        fit = _drawn_in(fit, planes)
    monitor.report(1.0, "grid: the crossings")
    return fit


def _printed(source, works, plane: Plane, hints, steps, tried, geographic: bool, threshold: float
             ) -> Optional["Placed"]:
    """The lattice in ``plane`` at the largest steps of ``steps`` (a list for each axis) whose lines are printed
    (beyond ``threshold``: the lattices a search may try share :data:`hamta.core.grid.lattice.CHANCE`): a family
    whose lines are not is tried at its next smaller step; None where no lattice is. Each lattice placed is added
    to ``tried``."""
    ix, iy = 0, 0
    while ix < len(steps[0]) and iy < len(steps[1]):
        step = (steps[0][ix], steps[1][iy])
        found = place_lattice(source, works, plane, hints, step, threshold=threshold)
        tried.append(Attempt(plane.name, step, None if found is None else found.evidence,
                             math.nan if found is None else found.spacing,
                             math.nan if found is None else found.lattice.straight))
        if found is None:  # a step wider than the sheet can judge, or one whose crossings are closer than printed:
            if too_fine(source, plane, hints, step):  # none smaller is printed
                return None
            few = few_lines(source, plane, hints, step)  # the family whose lines the sheet holds fewer than two of
            ix, iy = ix + (few[0] or not any(few)), iy + (few[1] or not any(few))
            continue
        if found.evidence.printed:
            return _equal_steps(source, works, plane, hints, steps, found, tried, threshold)
        fx, fy = (family.at_step for family in found.evidence.families)
        if fx and fy:
            return None  # each family at its step, but not both together beyond chance: no grid of these steps
        if not fx and not fy:  # the coarser family first: a lattice wrong one way misplaces the other's lines too
            coarser = int(np.argmax(np.hypot(*found.steps_px.T)))
            fx, fy = coarser == 1, coarser == 0
        ix, iy = ix + (not fx), iy + (not fy)
    return None


def _equal_steps(source, works, plane, hints, steps, found, tried, threshold):
    """``found``, or the lattice with both steps the larger of its two where that is printed too (a family at
    half its printed step still finds every printed line: the larger step is the grid's)."""
    sx, sy = found.step
    if sx == sy:
        return found
    both = max(sx, sy)
    if both not in steps[0] or both not in steps[1]:
        return found
    again = place_lattice(source, works, plane, hints, (both, both), threshold=threshold)
    tried.append(Attempt(plane.name, (both, both), None if again is None else again.evidence,
                         math.nan if again is None else again.spacing,
                         math.nan if again is None else again.lattice.straight))
    return again if again is not None and again.evidence.printed else found


def _drawn_in(fit: SheetFit, planes) -> SheetFit:
    """``fit`` in the plane where an affine predicts the crossings' grid lines, each held out in turn, best (the
    projection the sheet is drawn in: its lines straight and evenly spaced); the lattice's where none is 10 %
    better. ``fit.plane_fits``: each plane's held-out RMS (scan px)."""
    from .crossings import lines_held_out

    def held_out(plane):
        xy = plane.forward(fit.crossings[:, 4:6])
        if not np.isfinite(xy).all() or len(xy) < 4:
            return math.inf, xy
        errors = lines_held_out(xy, fit.crossings[:, :2], fit.crossings[:, 4:6],
                                lambda s, d: LinearModel.fit("affine", s, d).apply, 3)[0]
        return float(np.sqrt(np.mean(np.sum(errors ** 2, axis=1)))), xy

    scored = {p.name: (p,) + held_out(p) for p in planes}
    fit.plane_fits = {name: rms for name, (_, rms, _) in scored.items()}
    best = min(scored.values(), key=lambda t: t[1])
    if best[1] < 0.9 * scored[fit.plane.name][1]:
        crossings = fit.crossings.copy()
        crossings[:, 2:4] = best[2]
        fit.crossings, fit.plane = crossings, best[0]
        fit.order = ordered(crossings)
    return fit


def _not_found(tried: List[Attempt], geographic: bool, placed_by_hand: bool = True) -> str:
    what = "the hints" if placed_by_hand else "the labels read"
    check = ("Check the hints' coordinates and the grid's step" if placed_by_hand else
             "Give two or three crossings with their coordinates as hints (a QGIS Georeferencer .points file)")
    seen = [a for a in tried if a.evidence is not None]
    if not seen:
        return (f"No lattice of the step {what} give can be placed on the sheet (its crossings would be closer than "
                f"{MIN_STEP_PX:g} px or more than {MAX_CROSSINGS}). {check}.")
    best = max(seen, key=lambda a: a.evidence.score)
    return (f"No printed grid was found where {what} put it: tried {len(tried)} lattices "
            f"(steps {', '.join(sorted({describe_pair(a.step, geographic) for a in tried}))}); the best, "
            f"{describe_pair(best.step, geographic)} in {best.plane}: {best.evidence.text()}. {check}, "
            "or register the sheet onto a reference layer.")


def _lon_lat_box(hints, shape):
    """(west, south, east, north) degrees the sheet covers, from the hints by a similarity on longitudes shrunk by
    the cosine of their latitude (a first look: the planes need only their centre and span)."""
    lat0 = float(np.mean(hints[:, 3]))
    shrink = max(math.cos(math.radians(lat0)), 0.05)
    xy = hints[:, 2:] * [shrink, 1.0]
    model = first_model(hints[:, :2], xy).inverse()  # scan px -> shrunk degrees
    h, w = shape
    edge = model.apply(np.array([[x, y] for x in np.linspace(0, w, 5) for y in np.linspace(0, h, 5)]))
    lon, lat = edge[:, 0] / shrink, np.clip(edge[:, 1], -89.9, 89.9)
    return float(lon.min()), float(lat.min()), float(lon.max()), float(lat.max())


def _check_hints(hints, hint_xy, model, spacing) -> None:
    """Each hint within :data:`HINT_PX` of a step from where the lattice puts its coordinates, else the hint
    is named as the one that disagrees."""
    off = np.hypot(*(model.apply(hint_xy) - hints[:, :2]).T)
    for i in np.flatnonzero(off > HINT_PX * spacing):
        raise InputError(f"The printed grid found from the hints does not pass through hint {i + 1} ({hints[i, 2]:g}, "
                         f"{hints[i, 3]:g}): it puts those coordinates {off[i]:.0f} px away. Check that hint's "
                         "coordinates and place; if they are right, the grid is too faint here to be followed: "
                         "register the sheet onto a reference layer.")


