"""Keyword arguments as the command's flags: one mapping, so both mean the same."""

import math
import numbers


def to_flags(options):
    """``{"dir": (-1, -2, -3), "hidden": True}`` -> ``["--dir=-1.0,-2.0,-3.0", "--hidden"]``.

    ``None`` and ``False`` leave a flag out; ``True`` gives it bare; a sequence is joined
    with commas, and a sequence of sequences repeats the flag (``section=[(0, 0, 0, 1, 0, 0),
    (0, 0, 0, 0, 1, 0)]``: two planes); numbers are written so that they read back exactly
    (``repr`` of a float).
    """
    flags = []
    for key, value in options.items():
        if value is None or value is False:
            continue
        name = "--" + key.replace("_", "-")
        if value is True:
            flags.append(name)
        elif isinstance(value, str):
            flags.append(f"{name}={value}")
        elif _is_sequence(value) and len(value) > 0 and all(
            _is_sequence(v) and not isinstance(v, str) for v in value
        ):
            for v in value:
                flags.append(f"{name}=" + ",".join(_number(x, key) for x in v))
        elif _is_sequence(value):
            flags.append(f"{name}=" + ",".join(_number(v, key) for v in value))
        else:
            flags.append(f"{name}={_number(value, key)}")
    return flags


def _is_sequence(value):
    return hasattr(value, "__len__") and hasattr(value, "__getitem__")


def _number(value, key):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{key}: expected numbers, got {value!r}")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{key}: {value} is not a finite number")
    return repr(value)
