"""Turning values read with h5py into plain Python values.

The C++ writer may store a string as a fixed-length or a variable-length HDF5
string; h5py then hands back `str`, `bytes`, `numpy.bytes_` or an object array
of either. Everything here accepts all of those.
"""
import h5py
import numpy as np


def _is_text(value):
    return isinstance(value, (str, bytes, np.bytes_, np.str_))


def to_text(value):
    """Any attribute or dataset value as one string (arrays joined by ", ")."""
    if isinstance(value, h5py.Empty) or value is None:
        return ""
    if isinstance(value, (bytes, np.bytes_)):
        return bytes(value).decode("utf-8", errors="replace").rstrip("\0")
    if isinstance(value, np.ndarray):
        return ", ".join(to_text(v) for v in value.reshape(-1))
    return str(value)


def to_text_list(value):
    """A string or an array of strings as a list of strings."""
    if isinstance(value, h5py.Empty) or value is None:
        return []
    if isinstance(value, np.ndarray):
        return [to_text(v) for v in value.reshape(-1)]
    return [to_text(value)]


def to_scalar(value):
    """A parameter value: int, float, bool or str (1-element arrays unwrapped)."""
    if isinstance(value, h5py.Empty) or value is None:
        return ""
    if isinstance(value, np.ndarray):
        if value.size == 1:
            return to_scalar(value.reshape(-1)[0])
        return to_text(value)
    if _is_text(value):
        return to_text(value)
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value)
    return to_text(value)


def to_float(value, default=float("nan")):
    """A number attribute as float; strings are parsed; anything else -> default."""
    scalar = to_scalar(value)
    if isinstance(scalar, str):
        try:
            return float(scalar)
        except ValueError:
            return default
    return float(scalar)


def attr_text(obj, name, default=""):
    return to_text(obj.attrs[name]) if name in obj.attrs else default


def attr_float(obj, name, default=float("nan")):
    return to_float(obj.attrs[name], default) if name in obj.attrs else default


def is_string_dataset(dataset):
    return h5py.check_string_dtype(dataset.dtype) is not None


def read_floats(group, name):
    """A numeric dataset as a 1-D float array (empty if absent)."""
    if name not in group:
        return np.zeros(0)
    return np.asarray(group[name][()], dtype=float).reshape(-1)


def read_column(dataset):
    """A /runs column: a list of str for string datasets, else a float array."""
    data = dataset[()]
    if is_string_dataset(dataset):
        return to_text_list(data)
    return np.asarray(data, dtype=float).reshape(-1)
