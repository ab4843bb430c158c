"""Shared helpers of the paper scripts (scripts/paper/fig*.py, speed_accuracy.py): run a deck
through scpdyn when its outputs are missing (keeping runs that stop with an error: they are
results too), read the CSV outputs, and score histories (verification.md 0.3).

The binary is $SCPDYN_BIN if set, else build/bin/scpdyn of the repository. Runs use
OMP_NUM_THREADS=1 unless the caller's environment sets it (the wall times of the speed charts
are single-core times).
"""
import csv
import json
import os
import re
import subprocess

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OUT = os.path.join(ROOT, "out", "paper")


def save_figure(fig, name):
    """Writes out/paper/<name>.png and says so."""
    os.makedirs(OUT, exist_ok=True)
    png = os.path.join(OUT, name + ".png")
    fig.savefig(png, dpi=120)
    print("wrote", os.path.relpath(png, ROOT))


def binary():
    return os.environ.get("SCPDYN_BIN", os.path.join(ROOT, "build", "bin", "scpdyn"))


def deck_path(name):
    return os.path.join(ROOT, "inputs", "paper", name + ".yaml")


def run(deck, out, force=False, text=None, quiet=False):
    """Runs `deck` into `out` unless out/summary.json exists (or `force`). With `text`, that deck
    text is written to out/<deck name> and run instead (variants of a committed deck). Returns
    the summary dict; a run that stopped with an error has status "failed" and its message in
    "error" (exit status 3 keeps the outputs so far). Input errors (exit 2) raise."""
    summary = os.path.join(out, "summary.json")
    if force or not os.path.exists(summary):
        os.makedirs(out, exist_ok=True)
        path = deck
        if text is not None:
            path = os.path.join(out, os.path.basename(deck))
            with open(path, "w") as f:
                f.write(text)
        env = dict(os.environ)
        env.setdefault("OMP_NUM_THREADS", "1")
        env.setdefault("OMP_PROC_BIND", "false")
        if not quiet:
            print(f"running {os.path.relpath(path, ROOT)} -> {os.path.relpath(out, ROOT)}",
                  flush=True)
        r = subprocess.run([binary(), path, "-o", out], env=env, stdout=subprocess.DEVNULL,
                           stderr=subprocess.PIPE, text=True)
        if r.returncode not in (0, 3) or not os.path.exists(summary):
            raise RuntimeError(f"{path}: scpdyn exit status {r.returncode}\n{r.stderr[-2000:]}")
    with open(summary) as f:
        return json.load(f)


def failed(summary):
    return summary.get("status") != "completed"


def short_error(summary, n=90):
    """The first words of a failed run's message (for legends and tables)."""
    e = summary.get("error", "")
    m = re.match(r"(contact diverged at cycle \d+, time [0-9.e+-]+ s)", e)
    return m.group(1) if m else e[:n]


def read_csv(path):
    """Columns of a CSV file as numpy arrays, by header name."""
    with open(path) as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        return {h: np.zeros(0) for h in rows[0]} if rows else {}
    data = np.array(rows[1:], dtype=float)
    return {h: data[:, k] for k, h in enumerate(rows[0])}


def gauges(out):
    return read_csv(os.path.join(out, "gauges.csv"))


def history(out):
    return read_csv(os.path.join(out, "history.csv"))


def arrival(t, v, threshold):
    """First time v > threshold, linearly interpolated between samples; None if never."""
    k = np.nonzero(v > threshold)[0]
    if len(k) == 0:
        return None
    i = k[0]
    if i == 0:
        return t[0]
    return t[i - 1] + (threshold - v[i - 1]) * (t[i] - t[i - 1]) / (v[i] - v[i - 1])


def e2_norm(signals, references, window):
    """E_2 of verification.md 0.3: sqrt(sum_g int (q - q_ref)^2 dt / sum_g int q_ref^2 dt) over
    `window` (t0, t1); signals and references are lists of (t, q) pairs, each interpolated on a
    common grid of 2000 points (linear interpolation; the runs sample every cycle). A signal
    that ends before t1 (a stopped run) gives None."""
    t = np.linspace(window[0], window[1], 2001)
    num = den = 0.0
    for (ts, qs), (tr, qr) in zip(signals, references):
        if len(ts) == 0 or ts[-1] < window[1] * (1 - 1e-6):
            return None
        a = np.interp(t, ts, qs)
        b = np.interp(t, tr, qr)
        num += np.trapz((a - b) ** 2, t)
        den += np.trapz(b ** 2, t)
    return float(np.sqrt(num / den))


def total_variation(t, q, window):
    """Total variation sum |q_{k+1} - q_k| of the samples inside `window` (every cycle is a
    sample), divided by the range max - min there: 1 for a monotone signal, 2 for one rise and
    fall, larger for every oscillation."""
    m = (t >= window[0]) & (t <= window[1])
    s = q[m]
    if len(s) < 2:
        return float("nan")
    rng = s.max() - s.min()
    return float(np.sum(np.abs(np.diff(s))) / rng) if rng > 0 else 0.0


def cost(summary):
    return (f"{summary['elements']} cells, {summary['cycles']} cycles, "
            f"{summary['wall_time']:.2f} s wall ({summary['threads']} thread(s))")
