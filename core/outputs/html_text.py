"""The report's small HTML helpers: escaping, numbers, two-column and headed tables, figures and
colour swatches. They format values as given (any unit) and return escaped HTML.
"""
from __future__ import annotations

import html
import math
from typing import Iterable, Sequence, Tuple


def _e(value) -> str:
    return html.escape(str(value), quote=True)


def _num(value, fmt: str = ".3f", unit: str = "") -> str:
    """A number for the page; '–' when missing or not finite."""
    if value is None:
        return "–"
    if isinstance(value, (bool, str)):
        return _e(value)
    f = float(value)
    return _e(format(f, fmt) + unit) if math.isfinite(f) else "–"


def _rows(pairs: Iterable[Tuple[str, str]], numeric: bool = True) -> str:
    """A two-column table; values are HTML already escaped by the caller; ``numeric`` right-aligns them."""
    td = "<td class=n>" if numeric else "<td>"
    return "<table>" + "".join(f"<tr><th>{_e(k)}</th>{td}{v}</td></tr>" for k, v in pairs) + "</table>"


def _table(header: Sequence[str], rows: Iterable[Sequence[str]], numeric: Sequence[bool] = ()) -> str:
    """A table with ``header``; cells are escaped HTML; ``numeric`` right-aligns columns."""
    head = "".join(f"<th>{_e(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td{' class=n' if i < len(numeric) and numeric[i] else ''}>{c}</td>"
                                     for i, c in enumerate(r)) + "</tr>" for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def _figure(src: str, alt: str, caption: str, width: int, height: int) -> str:
    return (f'<figure><img src="{src}" alt="{_e(alt)}" width={width} height={height}>'
            f"<figcaption>{caption}</figcaption></figure>")


def _swatch(bgr, symbol: str, label: str) -> str:
    b, g, r = bgr
    return f'<span class=swatch style="color:rgb({r},{g},{b});text-shadow:0 0 1px #000">{symbol}</span> {_e(label)}'
