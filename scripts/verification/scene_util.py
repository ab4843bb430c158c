"""Shared helpers of the verification plot scripts: run a deck (or a mesh variant of it)
through scpdyn when its outputs are missing, read history/gauge CSV files and fields.h5 frames.

The binary is $SCPDYN_BIN if set, else build/bin/scpdyn of the repository.
"""
import csv
import json
import os
import re
import subprocess

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def binary():
    return os.environ.get("SCPDYN_BIN", os.path.join(ROOT, "build", "bin", "scpdyn"))


def deck_path(name):
    return os.path.join(ROOT, "inputs", "verification", name + ".yaml")


def run(deck, out, elements=None, force=False, substitutions=()):
    """Runs `deck` into `out` unless out/summary.json exists. With `elements` (a list), the
    deck's single `elements: [...]` entry is replaced; each (pattern, text) of `substitutions`
    replaces its one match. A variant deck is written into out. Returns the summary dict."""
    summary = os.path.join(out, "summary.json")
    if force or not os.path.exists(summary):
        os.makedirs(out, exist_ok=True)
        path = deck
        subs = list(substitutions)
        if elements is not None:
            subs.append((r"elements: \[[0-9, ]+\]", "elements: [" + ", ".join(str(e) for e in elements) + "]"))
        if subs:
            text = open(deck).read()
            for pattern, replacement in subs:
                text, n = re.subn(pattern, replacement, text)
                if n != 1:
                    raise RuntimeError(f"{deck}: expected one match of '{pattern}', found {n}")
            path = os.path.join(out, os.path.basename(deck))
            with open(path, "w") as f:
                f.write(text)
        env = dict(os.environ)
        env.setdefault("OMP_PROC_BIND", "false")
        print(f"running {os.path.basename(path)} -> {out}", flush=True)
        subprocess.run([binary(), path, "-o", out], check=True, env=env,
                       stdout=subprocess.DEVNULL)
    with open(summary) as f:
        return json.load(f)


def read_csv(path):
    """Columns of a CSV file as numpy arrays, by header name."""
    with open(path) as f:
        rows = list(csv.reader(f))
    data = np.array(rows[1:], dtype=float)
    return {h: data[:, k] for k, h in enumerate(rows[0])}


class Fields:
    """Frames of out/fields.h5 (sorted by time) with the mesh."""

    def __init__(self, out):
        import h5py

        self.file = h5py.File(os.path.join(out, "fields.h5"), "r")
        self.coords0 = self.file["mesh/coords0"][()]
        self.topology = self.file["mesh/topology"][()]
        frames = self.file["frames"]
        self.keys = sorted(frames.keys(), key=int)
        self.times = np.array([frames[k].attrs["time"] for k in self.keys])

    def frame(self, k):
        """k-th frame (negative counts from the end): coords and cell data as a dict."""
        g = self.file["frames"][self.keys[k]]
        d = {name: g["cell_data"][name][()] for name in g["cell_data"]}
        d["coords"] = g["coords"][()]
        d["time"] = float(g.attrs["time"])
        return d

    def centroids(self, coords):
        return coords[self.topology].mean(axis=1)

    def nearest_element(self, point):
        """The element a gauge at `point` reads: nearest initial centroid (as the solver)."""
        c = self.centroids(self.coords0)
        p = np.zeros(3)
        p[: len(point)] = point
        return int(np.argmin(np.sum((c - p) ** 2, axis=1)))


def gauge_points(out):
    """name -> point of the run's gauges (from deck.resolved.yaml)."""
    import yaml

    with open(os.path.join(out, "deck.resolved.yaml")) as f:
        deck = yaml.safe_load(f)
    return {g["name"]: g["point"] for g in deck.get("gauges", []) if "point" in g}


def cost(summary):
    return (f"{summary['elements']} cells, {summary['cycles']} cycles, "
            f"{summary['wall_time']:.1f} s wall ({summary['threads']} thread(s))")
