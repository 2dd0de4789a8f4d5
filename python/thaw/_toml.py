"""Python values -> TOML text, for thaw.Scenario.from_dict / .with_ and scene dicts.

The text is parsed by thaw's own parser afterwards, so every rule (types, ranges, unknown keys)
is the file's rule. Tables become [sections], lists of dicts [[arrays of tables]], dicts inside
other lists inline tables. Floats are written with repr(), which reads back to the same double.
"""
import json
import math
import re

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k):
    if not isinstance(k, str):
        raise TypeError(f"TOML keys are strings (got {k!r})")
    return k if _BARE.match(k) else json.dumps(k, ensure_ascii=False)


def _value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if hasattr(v, "tolist"):  # NumPy scalars and arrays
        return _value(v.tolist())
    if hasattr(v, "__fspath__"):
        return _value(str(v.__fspath__()))
    raise TypeError(f"no TOML form for {type(v).__name__} value {v!r}")


def _is_table_array(v):
    return isinstance(v, (list, tuple)) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def _table(d, path, out):
    plain = [(k, v) for k, v in d.items() if not isinstance(v, dict) and not _is_table_array(v)]
    for k, v in plain:
        out.append(f"{_key(k)} = {_value(v)}")
    for k, v in d.items():
        sub = path + [_key(k)]
        if isinstance(v, dict):
            out.append("")
            out.append("[" + ".".join(sub) + "]")
            _table(v, sub, out)
        elif _is_table_array(v):
            for item in v:
                out.append("")
                out.append("[[" + ".".join(sub) + "]]")
                _table(item, sub, out)


def dumps(d):
    """TOML text of the nested dict ``d``."""
    if not isinstance(d, dict):
        raise TypeError(f"a TOML document is a dict (got {type(d).__name__})")
    out = []
    _table(d, [], out)
    return "\n".join(out).lstrip("\n") + "\n"


def set_dotted(d, dotted, value):
    """Sets d["a"]["b"] = value for dotted = "a.b", making tables on the way."""
    parts = dotted.split(".")
    node = d
    for p in parts[:-1]:
        nxt = node.get(p)
        if nxt is None:
            nxt = node[p] = {}
        elif not isinstance(nxt, dict):
            return False
        node = nxt
    node[parts[-1]] = value
    return True
