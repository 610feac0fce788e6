"""A small TOML writer for the bad-input corpus and the fuzzer (the standard library only reads TOML).

Writes nested dicts as tables, lists of dicts as arrays of tables, and numbers, strings, booleans
and (nested) lists as values; ``nan``/``inf`` as TOML's own spellings. Enough for catalog and
snapshot files; values TOML cannot hold (None, objects) are written as their ``repr`` inside a
string so the reader sees *something* of the wrong type.
"""

import json
import math


def value_text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list):
        return "[" + ", ".join(value_text(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(str(k))} = {value_text(v)}" for k, v in value.items()) + "}"
    return json.dumps(repr(value))


def _is_table_array(value):
    return isinstance(value, list) and value and all(isinstance(v, dict) for v in value)


def toml_text(data, prefix=""):
    """TOML text of a mapping (round-trips through :mod:`tomllib` for plain data)."""
    lines, tables = [], []
    for key, value in data.items():
        name = json.dumps(str(key))
        if isinstance(value, dict) and value:
            tables.append((name, value))
        elif _is_table_array(value):
            tables.append((name, value))
        else:
            lines.append(f"{name} = {value_text(value)}")
    for name, value in tables:
        full = f"{prefix}.{name}" if prefix else name
        if isinstance(value, dict):
            lines.append(f"\n[{full}]")
            lines.append(toml_text(value, full))
        else:
            for item in value:
                lines.append(f"\n[[{full}]]")
                lines.append(toml_text(item, full))
    return "\n".join(lines)
