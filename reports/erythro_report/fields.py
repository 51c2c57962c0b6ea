"""Field pictures of a record: /fields/<name> (optional; layout in docs/reports.md).

    /fields/<name>              group, one picture
        data                    float dataset, 2-D [y, x]; 3-D [z, y, x] is shown as its middle z slice
        x, y                    optional 1-D cell-centre coordinates (default: node index)
        attrs title, quantity, unit, xlabel, ylabel   text, all optional
        membranes/<k>           optional (n, 2) float datasets: closed outlines (x, y) drawn on top
"""
from dataclasses import dataclass, field
from typing import Optional

import h5py
import numpy as np

from .h5text import attr_text


class FieldError(Exception):
    """A /fields group that cannot be drawn as written."""


@dataclass
class Field:
    name: str
    title: str
    quantity: str
    unit: str
    xlabel: str
    ylabel: str
    data: np.ndarray                  # 2-D, indexed [y, x]
    x: Optional[np.ndarray] = None    # cell-centre coordinates, or None (node index)
    y: Optional[np.ndarray] = None
    membranes: list = field(default_factory=list)   # (n, 2) arrays: x, y of outlines


def read_field(name, group, path):
    if "data" not in group or not isinstance(group["data"], h5py.Dataset):
        raise FieldError(f"{path}: /fields/{name} has no dataset 'data'")
    data = np.asarray(group["data"][()], dtype=float)
    if data.ndim == 3:
        data = data[data.shape[0] // 2]
    if data.ndim != 2:
        raise FieldError(f"{path}: /fields/{name}/data is {data.ndim}-D, not 2-D or 3-D")
    x = _axis(group, "x", data.shape[1], name, path)
    y = _axis(group, "y", data.shape[0], name, path)
    membranes = []
    if "membranes" in group:
        for key in group["membranes"]:
            outline = np.asarray(group["membranes"][key][()], dtype=float)
            if outline.ndim != 2 or outline.shape[1] != 2:
                raise FieldError(f"{path}: /fields/{name}/membranes/{key} is not an (n, 2) array")
            membranes.append(outline)
    texts = {k: attr_text(group, k) for k in ("title", "quantity", "unit", "xlabel", "ylabel")}
    return Field(name=name, data=data, x=x, y=y, membranes=membranes, **texts)


def _axis(group, key, n, name, path):
    if key not in group:
        return None
    values = np.asarray(group[key][()], dtype=float).reshape(-1)
    if len(values) != n:
        raise FieldError(f"{path}: /fields/{name}/{key} has {len(values)} values for {n} cells")
    return values
