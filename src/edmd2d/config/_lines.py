"""The messages and source lines of a configuration's errors.

TOML parsers give no line numbers for keys, so the line of each key and table is found
by scanning the text (:func:`_key_lines`); a key path is shown dotted (:func:`_dotted`),
and an unknown name comes with the closest known one (:func:`_unknown`).
"""

from __future__ import annotations

import difflib
import re


def _unknown(key: str, known, what: str = "key") -> str:
    close = difflib.get_close_matches(key, list(known), n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else (
        f" (known: {', '.join(map(str, known))})")
    return f"unknown {what}{hint}"


def _shown(value) -> str:
    kind = {str: "a string", bool: "a boolean", int: "an integer", float: "a number",
            list: "a list", dict: "a table"}.get(type(value), type(value).__name__)
    return f"{kind} {value!r}" if not isinstance(value, dict) else kind


def _dotted(key: tuple) -> str:
    out = ""
    for part in key:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else part)
    return out


def _line_of(lines: dict, key: tuple) -> int | None:
    """The line of ``key``, or of the nearest enclosing table or key that has one."""
    key = tuple(key)
    while key:
        if key in lines:
            return lines[key]
        key = key[:-1]
    return None


_HEADER = re.compile(r"^\s*(\[\[?)\s*([^\]]+?)\s*\]\]?\s*$")
_NAME = r"""(?:[A-Za-z0-9_-]+|"[^"]*"|'[^']*')"""  # (a bare or quoted key)
_KEY = re.compile(rf"^\s*({_NAME}(?:\s*\.\s*{_NAME})*)\s*=(.*)$")


def _split_key(key: str) -> tuple:
    parts = re.findall(_NAME, key)
    return tuple(p[1:-1] if p[:1] in "\"'" else p for p in parts)


def _strip_comment(line: str) -> str:
    quote = None
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "\"'":
            quote = ch
        elif ch == "#":
            return line[:i]
    return line


def _key_lines(text: str) -> dict:
    """Where each key and table of a TOML text is: ``{path: line}``, a path being the
    tuple of names (and indices of arrays of tables, ``("walls", 1, "start")``).

    A scan of the text, table header by table header: keys (also dotted and quoted)
    at the start of a line; the keys of an inline table ``{a = 1, b = 2}`` on the line
    of its key; the lines inside a value that spans several lines are skipped.
    """
    lines: dict = {}
    arrays: dict = {}
    table: tuple = ()
    depth = 0
    for number, raw in enumerate(text.splitlines(), start=1):
        line = _strip_comment(raw)
        if depth > 0:  # (inside a value of several lines: an array)
            depth += line.count("[") + line.count("{") - line.count("]") - line.count("}")
            continue
        header = _HEADER.match(line)
        if header:
            path = _split_key(header.group(2))
            if header.group(1) == "[[":
                k = arrays.get(path, 0)
                arrays[path] = k + 1
                lines.setdefault(path, number)
                path = path + (k,)
            else:
                # (a sub-table of the last element of an array of tables)
                for n in range(len(path) - 1, 0, -1):
                    if path[:n] in arrays:
                        path = path[:n] + (arrays[path[:n]] - 1,) + path[n:]
                        break
            table = path
            lines.setdefault(path, number)
            continue
        found = _KEY.match(line)
        if not found:
            continue
        path = table + _split_key(found.group(1))
        lines.setdefault(path, number)
        value = found.group(2)
        depth = value.count("[") + value.count("{") - value.count("]") - value.count("}")
        inline = value.strip()
        if inline.startswith("{"):
            for inner in re.finditer(r"([A-Za-z0-9_-]+)\s*=", inline):
                lines.setdefault(path + (inner.group(1),), number)
    return lines
