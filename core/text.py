"""Text from outside (a map server's answer, a file's metadata) made safe to print or write in a report."""
from __future__ import annotations

LIMIT = 200  # characters of outside text kept in a message


def printable(text, limit: int = LIMIT) -> str:
    """``text`` with every character Python does not call printable (controls: escape sequences, bell,
    carriage return, newline; format characters such as bidirectional overrides; separators other than
    the space) written as ``\\xNN`` or ``\\uNNNN``, cut to ``limit`` characters (then '…')."""
    text = str(text)
    cut = len(text) > limit
    out = []
    for ch in text[:limit]:
        if not ch.isprintable():
            code = ord(ch)
            out.append(f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}")
        else:
            out.append(ch)
    return "".join(out) + ("…" if cut else "")


def terminal_safe(text: str) -> str:
    """``text`` for a terminal: newline, tab and carriage return kept (Hamta's own layout and progress bar),
    every other control or format character escaped: a message may quote outside text, and none of it may
    move the cursor, clear the screen or set the window's title."""
    if text.isprintable():
        return text
    return "".join(ch if ch in "\n\t\r" else printable(ch) for ch in text)
