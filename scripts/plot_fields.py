#!/usr/bin/python3
"""Draw a field of a run on its deformed mesh at chosen times.

usage: /usr/bin/python3 scripts/plot_fields.py OUTDIR [OUTDIR2] [--field NAME] [--times T ...]
           [--edges] [--contacts] [--mirror] [--camera X Y Z] [--up X Y Z] [--out PNG]

Reads OUTDIR/fields.h5 (the frames fields.xmf names). Each requested time (in s) is drawn at
the nearest written frame, whose time the panel title gives. One colour scale for every panel,
one colour bar with the field's unit. With OUTDIR2 each time is a row: OUTDIR left, OUTDIR2
right (e.g. continuum left, jointed right).

2D: matplotlib; element fields flat per element, nodal fields interpolated (gouraud).
3D: a ParaView render of fields.xmf (pvbatch, under xvfb-run without a display), one image per
frame, combined into one PNG.

  --field NAME   default pressure; a wrong name lists the fields the run has
  --times T ...  default: the frames nearest 1/3, 2/3 and all of the written time
  --edges        mesh edges as thin lines
  --contacts     the contact points (contacts.h5) of the same frame as dots; failed sleepy
                 joints as larger magenta dots
  --mirror       2D: mirror a quarter model about x = 0 and y = 0 (symmetry planes)
  --camera X Y Z 3D: the direction from the model's centre to the camera (default 1 0.8 1.6)
  --up X Y Z     3D: the direction that is up in the picture (default 0 1 0; 0 0 1 for a
                 deck with gravity along -z)
  --out PNG      default OUTDIR/fields_<field>.png

Prints `plot_fields: wrote PNG field NAME range MIN MAX` (SI units, over the drawn frames).
The fields and their units: README.md, "Pictures". Eroded elements (the cell field `eroded`
of a deck whose material erodes) are not drawn.
Exit status 2 on a bad argument (no fields.h5, unknown field, time outside the frames).
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

# Unit (SI) and sign convention of the fields scpdyn writes (docs/input.md, gauges); "" is
# dimensionless. A field not listed still plots, without a unit.
UNITS = {
    "pressure": ("Pa", "compression +"), "von_mises": ("Pa", ""),
    "tensile_strength": ("Pa", ""), "density": ("kg/m³", ""),
    "specific_internal_energy": ("J/kg", ""), "plastic_strain": ("", ""),
    "plastic_volumetric_strain": ("", ""), "damage": ("", ""), "burn_fraction": ("", ""),
    "part": ("", "index, summary.json parts"), "lighting_time": ("s", ""),
    "temperature": ("K", ""), "plastic_strain_rate": ("1/s", ""),
    "velocity": ("m/s", "magnitude"), "displacement": ("m", "magnitude"),
}
UNITS.update({"s" + c: ("Pa", "tension +") for c in ("xx", "yy", "zz", "xy", "yz", "zx")})
UNITS.update({p + c: (u, "") for p, u in (("v", "m/s"), ("d", "m")) for c in "xyz"})
# the prefixes a unit is shown with: the largest whose factor is below the values
PREFIXES = {
    "Pa": [(1e9, "GPa"), (1e6, "MPa"), (1e3, "kPa"), (1.0, "Pa")],
    "J/kg": [(1e6, "MJ/kg"), (1e3, "kJ/kg"), (1.0, "J/kg")],
    "m": [(1.0, "m"), (1e-3, "mm"), (1e-6, "µm")],
    "s": [(1.0, "s"), (1e-3, "ms"), (1e-6, "µs"), (1e-9, "ns")],
}
# fields.h5 stores the stress as XDMF Tensor6 (xx xy xz yy yz zz); ParaView reads it as 3x3
STRESS = {"sxx": (0, 0, 0), "syy": (3, 1, 1), "szz": (5, 2, 2), "sxy": (1, 0, 1),
          "syz": (4, 1, 2), "szx": (2, 0, 2)}


class UsageError(Exception):
    pass


def prefixed(unit, magnitude):
    """(factor, shown unit) for values up to `magnitude` in `unit`."""
    choices = PREFIXES.get(unit, [(1.0, unit)])
    for factor, name in choices:
        if magnitude >= factor:
            return factor, name
    return choices[-1]


def fmt_time(t):
    f, u = prefixed("s", abs(t) if t else 1e-6)
    return f"{t / f:.3g} {u}"


class Run:
    """One output directory: the frames of fields.h5 that fields.xmf names (a frame is on
    disk before the XDMF file names it), and contacts.h5 when the deck has contact."""

    def __init__(self, out_dir):
        import h5py
        path = os.path.join(out_dir, "fields.h5")
        if not os.path.exists(path):
            raise UsageError(f"OUTDIR '{out_dir}': no fields.h5 (not a scpdyn output directory?)")
        self.dir = out_dir
        self.name = os.path.basename(os.path.normpath(out_dir))
        self.h5 = h5py.File(path, "r")
        self.dim = int(self.h5["mesh"].attrs["dim"])
        keys = sorted(self.h5["frames"], key=int)
        xmf = os.path.join(out_dir, "fields.xmf")
        if os.path.exists(xmf):
            with open(xmf) as f:
                named = set(re.findall(r"fields\.h5:/frames/(\d+)/coords", f.read()))
            keys = [k for k in keys if k in named]
        if not keys:
            raise UsageError(f"OUTDIR '{out_dir}': fields.h5 has no complete frame")
        self.frames = [self.h5["frames"][k] for k in keys]
        self.times = np.array([float(f.attrs["time"]) for f in self.frames])
        mesh = self.h5["mesh"]
        self.cells = mesh["topology"][()] if "topology" in mesh else None
        cpath = os.path.join(out_dir, "contacts.h5")
        self.contacts = h5py.File(cpath, "r") if os.path.exists(cpath) else None
        self.axisymmetric = False
        deck = os.path.join(out_dir, "deck.resolved.yaml")
        if os.path.exists(deck):
            with open(deck) as f:
                self.axisymmetric = bool(re.search(r"^geometry: *axisymmetric", f.read(), re.M))

    def fields(self):
        """name -> ("cell" or "node", function(frame) -> values) of the fields of this run."""
        f0, dim, out = self.frames[0], self.dim, {}
        for name, d in f0["cell_data"].items():
            if d.ndim == 1:
                out[name] = ("cell", lambda fr, n=name: fr["cell_data"][n][()])
        if "stress" in f0["cell_data"]:
            for name, (k, _, _) in STRESS.items():
                if dim == 3 or name in ("sxx", "syy", "szz", "sxy"):
                    out[name] = ("cell", lambda fr, k=k: fr["cell_data/stress"][:, k])
            out["von_mises"] = ("cell", lambda fr: von_mises(fr["cell_data/stress"][()]))
        for vec in ("velocity", "displacement"):
            if vec in f0["point_data"]:
                for c in range(dim):
                    out[vec[0] + "xyz"[c]] = (
                        "node", lambda fr, v=vec, c=c: fr["point_data"][v][:, c])
                out[vec] = ("node", lambda fr, v=vec: np.linalg.norm(
                    fr["point_data"][v][:, :dim], axis=1))
        return out

    def frame_at(self, t):
        """Index of the written frame nearest time t; a time outside the frames is an error."""
        lo, hi = self.times[0], self.times[-1]
        slack = 1e-3 * (hi - lo) + 1e-15  # a frame is written at the first cycle past its time
        if t < lo - slack or t > hi + slack:
            raise UsageError(f"--times: {t:g} s is outside the frames of '{self.dir}' "
                             f"({lo:g} to {hi:g} s, {len(self.times)} frames)")
        return int(np.argmin(np.abs(self.times - t)))

    def contact_frame(self, k):
        """The contact frame at field frame k's time, or None (none written then, or no CPs)."""
        if self.contacts is None:
            return None
        frames = self.contacts["frames"]
        times = {key: float(frames[key].attrs["time"]) for key in frames}
        key = min(times, key=lambda q: abs(times[q] - self.times[k]))
        if abs(times[key] - self.times[k]) > 1e-12 * max(1.0, abs(self.times[k])):
            return None
        frame = frames[key]
        # a frame without CPs holds one placeholder point whose values are all -1
        if len(frame["points"]) == 1 and frame["point_data/area"][0] == -1:
            return None
        return frame

    def contact_points(self, k):
        """(n, 3) contact points of the contact frame at field frame k's time (none: (0, 3))."""
        frame = self.contact_frame(k)
        return np.zeros((0, 3)) if frame is None else frame["points"][()]

    def contact_failed(self, k):
        """Per contact point of contact_points(k): True for a sleepy CP that has failed."""
        frame = self.contact_frame(k)
        if frame is None or "point_data/failed" not in frame:
            return np.zeros(len(self.contact_points(k)), dtype=bool)
        return frame["point_data/failed"][()] > 0.5


def von_mises(s):
    """Von Mises stress of Tensor6 rows (xx xy xz yy yz zz)."""
    xx, xy, xz, yy, yz, zz = s.T
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                   + 3 * (xy ** 2 + yz ** 2 + xz ** 2))


def field_of(runs, name):
    """(centre, getter) of field `name`, which every run must have."""
    for run in runs:
        have = run.fields()
        if name not in have:
            raise UsageError(f"--field: '{name}' is not a field of '{run.dir}'; its fields: "
                             + ", ".join(sorted(have)))
    return runs[0].fields()[name]


def label_of(name, vmin, vmax):
    """(factor, colour bar label): the field's unit with a prefix that suits the range."""
    unit, note = UNITS.get(name, (None, ""))
    factor, shown = prefixed(unit, max(abs(vmin), abs(vmax))) if unit else (1.0, "")
    label = name + (f" [{shown}]" if shown else " [-]" if unit == "" else "")
    return factor, label + (f" ({note})" if note else "")


def select(runs, times):
    """Frame indices per run for each requested time (default: 1/3, 2/3, 3/3 of the run)."""
    if not times:
        t0, t1 = runs[0].times[0], runs[0].times[-1]
        times = [t0 + (t1 - t0) * q for q in (1 / 3, 2 / 3, 1)]
    rows = []
    for t in times:
        row = [run.frame_at(t) for run in runs]
        if not any(row == r for _, r in rows):  # two times on the same frames: one row
            rows.append((t, row))
    return rows


def live(frame, values):
    """`values` without those of eroded elements (cell values of a run whose material erodes)."""
    eroded = frame["cell_data"].get("eroded")
    if eroded is None or len(values) != len(eroded):
        return values
    return values[eroded[()] == 0]


def field_range(runs, rows, getter, signs=(1,)):
    vals = [s * live(run.frames[k], getter(run.frames[k])) for _, row in rows
            for run, k in zip(runs, row) for s in signs]
    lo, hi = min(np.nanmin(v) for v in vals), max(np.nanmax(v) for v in vals)
    return float(lo) + 0.0, float(hi) + 0.0  # + 0.0: no "-0.0" in the printed range


MIRRORS = [(1, 1), (-1, 1), (1, -1), (-1, -1)]


def mirror_sign(name, sx, sy):
    """Sign of field `name` in the copy mirrored by (sx, sy): x components flip with x."""
    return {"vx": sx, "dx": sx, "vy": sy, "dy": sy, "sxy": sx * sy}.get(name, 1)


def mirrored(values, name, signs):
    return np.concatenate([mirror_sign(name, *s) * values for s in signs])


def draw_panel(ax, run, k, name=None, centre="cell", values=None, norm=None, cmap="turbo",
               edges=False, contacts=False, mirror=False, length=1e-3):
    """Draws frame k of a 2D run on `ax` (lengths divided by `length`): coloured by `values`
    (per element or node), or with `name` None the bare mesh in light grey with its edges.
    Returns the colour mapping (None for the bare mesh)."""
    from matplotlib.collections import PolyCollection
    from matplotlib.tri import Triangulation
    xy = run.frames[k]["coords"][:, :2] / length
    cells = run.cells
    cell_data = run.frames[k]["cell_data"]
    if "eroded" in cell_data:  # an eroded element is gone from the body: not drawn
        live = cell_data["eroded"][()] == 0
        cells = cells[live]
        if centre == "cell" and values is not None:
            values = values[live]
    signs = MIRRORS if mirror else MIRRORS[:1]
    n = len(xy)
    xy_all = np.vstack([xy * s for s in signs])
    cells_all = np.vstack([cells + m * n for m in range(len(signs))])
    polys = xy_all[cells_all]
    lw = min(0.5, 25.0 / np.sqrt(len(cells_all)))  # thin enough that dense meshes stay readable
    mapping = None
    if name is None:
        ax.add_collection(PolyCollection(polys, facecolors="0.92", edgecolors="0.25",
                                         linewidths=lw))
    elif centre == "cell":
        mapping = PolyCollection(polys, array=mirrored(values, name, signs), cmap=cmap, norm=norm,
                                 edgecolors="k" if edges else "face",
                                 linewidths=lw if edges else 0.2)
        ax.add_collection(mapping)
    else:
        # quads split in two triangles for the gouraud interpolation of the nodal values
        tris = np.vstack([cells_all[:, [0, 1, 2]], cells_all[:, [0, 2, 3]]])
        mapping = ax.tripcolor(Triangulation(xy_all[:, 0], xy_all[:, 1], tris),
                               mirrored(values, name, signs), shading="gouraud", cmap=cmap,
                               norm=norm)
        if edges:
            ax.add_collection(PolyCollection(polys, facecolors="none", edgecolors="k",
                                             linewidths=lw))
    if contacts:
        pts = run.contact_points(k)[:, :2] / length
        failed = run.contact_failed(k)
        if len(pts):
            failed = np.concatenate([failed for s in signs])
            pts = np.vstack([pts * s for s in signs])
            # white shows on the dark low end of turbo, red among the bare mesh's black edges
            ax.scatter(pts[~failed, 0], pts[~failed, 1], s=2.0 if name is None else 1.0,
                       c="r" if name is None else "w", marker=".",
                       linewidths=0)
            # failed sleepy joints: larger, in a colour of their own
            ax.scatter(pts[failed, 0], pts[failed, 1], s=6.0, c="m", marker="o",
                       linewidths=0)
    ax.set_aspect("equal")
    ax.autoscale_view()
    return mapping


def extent(runs, rows, mirror=False):
    """Lower and upper corners of the drawn frames' coordinates (x, y)."""
    xy = [run.frames[k]["coords"][:, :2] for _, row in rows for run, k in zip(runs, row)]
    lo, hi = np.min([c.min(0) for c in xy], 0), np.max([c.max(0) for c in xy], 0)
    if mirror:
        hi = np.maximum(np.abs(lo), np.abs(hi))
        lo = -hi
    return lo, hi


def figure_2d(runs, rows, name=None, vrange=None, edges=False, contacts=False, mirror=False,
              width=3.6, cmap="turbo", values_of=None):
    """The figure of a 2D field (or with `name` None the bare meshes): a row of panels, or with
    two runs a row per time (runs[0] left); one colour scale over `vrange` (SI). `values_of`
    (run, frame) -> values replaces the field's own values (masked cells as NaN, drawn in the
    colour map's 'bad' colour)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import Normalize
    centre, getter = runs[0].fields()[name] if name else (None, None)
    factor, label = label_of(name, *vrange) if name else (1.0, "")
    norm = None
    if name:
        lo, hi = vrange
        norm = Normalize(lo / factor, (hi if hi > lo else lo + max(abs(lo), 1.0)) / factor)
    lo_xy, hi_xy = extent(runs, rows, mirror)
    length, lunit = prefixed("m", float(np.max(hi_xy - lo_xy)))
    aspect = float((hi_xy[1] - lo_xy[1]) / max(hi_xy[0] - lo_xy[0], 1e-30))
    two = len(runs) == 2
    nr, nc = (len(rows), 2) if two else (1, len(rows))
    height = min(max(width * aspect, 1.6), 8)
    fig, axes = plt.subplots(nr, nc, figsize=(width * nc + (1.2 if name else 0.4),
                                              height * nr + 0.6),
                             squeeze=False, constrained_layout=True)
    for i, (_, row) in enumerate(rows):
        for j, (run, k) in enumerate(zip(runs, row)):
            ax = axes[i, j] if two else axes[0, i]
            values = None
            if name:
                raw = values_of(run, run.frames[k]) if values_of else getter(run.frames[k])
                values = raw / factor
            m = draw_panel(ax, run, k, name, centre, values, norm, cmap=cmap, edges=edges,
                           contacts=contacts, mirror=mirror, length=length)
            ax.set_xlim(lo_xy[0] / length, hi_xy[0] / length)
            ax.set_ylim(lo_xy[1] / length, hi_xy[1] / length)
            ax.set_title(f"{run.name}: t = {fmt_time(run.times[k])} (frame {k})", fontsize=9)
            x, y = ("r", "z") if run.axisymmetric else ("x", "y")
            ax.set_xlabel(f"{x} [{lunit}]", fontsize=8)
            ax.set_ylabel(f"{y} [{lunit}]", fontsize=8)
            ax.tick_params(labelsize=7)
    if name:
        fig.colorbar(m, ax=axes.ravel().tolist(), shrink=0.85).set_label(label)
    return fig


def pv_expression(name, centre):
    """The field as a numpy expression of ParaView's arrays (PythonCalculator)."""
    if name in STRESS:
        _, i, j = STRESS[name]
        return f"stress[:,{i},{j}]"
    if name == "von_mises":
        s = {c: f"stress[:,{i},{j}]" for c, (_, i, j) in STRESS.items()}
        return (f"sqrt(0.5*(({s['sxx']}-{s['syy']})**2+({s['syy']}-{s['szz']})**2"
                f"+({s['szz']}-{s['sxx']})**2)+3*({s['sxy']}**2+{s['syz']}**2+{s['szx']}**2))")
    if name in ("velocity", "displacement"):
        return f"mag({name})"
    if centre == "node" and name[0] in "vd" and name[1:] in ("x", "y", "z"):
        return f"{dict(v='velocity', d='displacement')[name[0]]}[:,{'xyz'.index(name[1])}]"
    return name


def plot_3d(runs, rows, name, centre, vmin, vmax, args):
    """Renders each panel with pvbatch (this script, --pvbatch SPEC), then tiles them; the
    ranges ParaView coloured by must be the ones computed here from fields.h5."""
    factor, label = label_of(name, vmin, vmax)
    tmp = tempfile.mkdtemp(prefix="plot_fields_")
    try:
        getter = runs[0].fields()[name][1]
        # a contact frame without CPs holds a placeholder point at the origin: not drawn
        panels = [dict(xmf=os.path.abspath(os.path.join(run.dir, "fields.xmf")),
                       contacts=os.path.abspath(os.path.join(run.dir, "contacts.xmf"))
                       if args.contacts and len(run.contact_points(k)) else None,
                       time=float(run.times[k]), png=os.path.join(tmp, f"{i}_{j}.png"),
                       title=f"{run.name}: t = {fmt_time(run.times[k])} (frame {k})",
                       want=[x / factor for x in field_range([run], [(0, [k])], getter)])
                  for i, (_, row) in enumerate(rows) for j, (run, k) in enumerate(zip(runs, row))]
        spec = dict(panels=panels, expression=f"({pv_expression(name, centre)})/{factor!r}",
                    centre=centre, label=label, range=[vmin / factor, vmax / factor],
                    edges=args.edges, camera=args.camera, up=args.up,
                    result=os.path.join(tmp, "ranges.json"))
        with open(os.path.join(tmp, "spec.json"), "w") as f:
            json.dump(spec, f)
        cmd = ["pvbatch", os.path.abspath(__file__), "--pvbatch", os.path.join(tmp, "spec.json")]
        if not os.environ.get("DISPLAY") and shutil.which("xvfb-run"):
            # Debian's ParaView renders through X; without -noreset Xvfb resets when
            # pvbatch's probe of OpenGL disconnects, and the render window's connection fails
            cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24 -noreset"] + cmd
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if r.returncode != 0 or not os.path.exists(spec["result"]):
            sys.exit(f"plot_fields: pvbatch failed (exit {r.returncode}):\n{r.stdout[-3000:]}")
        with open(spec["result"]) as f:
            for p, (lo, hi) in zip(panels, json.load(f)):
                want = p["want"]
                if not np.allclose([lo, hi], want, rtol=1e-6, atol=1e-12 * max(map(abs, want))):
                    sys.exit(f"plot_fields: ParaView coloured {p['title']} by range {lo} {hi}, "
                             f"fields.h5 has {want[0]} {want[1]}")
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        nr, nc = (len(rows), 2) if len(runs) == 2 else (1, len(rows))
        fig, axes = plt.subplots(nr, nc, figsize=(4.5 * nc, 3.6 * nr), squeeze=False,
                                 constrained_layout=True)
        for ax, p in zip(axes.ravel() if nc == 2 else axes[0], panels):
            ax.imshow(plt.imread(p["png"]))
            ax.set_title(p["title"], fontsize=9)
            ax.axis("off")
        fig.savefig(args.out, dpi=150)
        plt.close(fig)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def pvbatch_main(spec_path):
    """Under pvbatch: one PNG per panel of the spec; writes the range of each coloured array."""
    from paraview import simple as pv
    with open(spec_path) as f:
        spec = json.load(f)
    ranges = []
    cells = spec["centre"] == "cell"
    for p in spec["panels"]:
        view = pv.CreateRenderView(ViewSize=[900, 700], OrientationAxesVisibility=1)
        view.UseColorPaletteForBackground, view.Background = 0, [1, 1, 1]
        view.ViewTime = p["time"]
        reader = pv.XDMFReader(FileNames=[p["xmf"]])
        calc = pv.PythonCalculator(Input=reader, Expression=spec["expression"], ArrayName="field",
                                   ArrayAssociation="Cell Data" if cells else "Point Data")
        calc.UpdatePipeline(p["time"])
        data = calc.CellData if cells else calc.PointData
        ranges.append(list(data["field"].GetRange()))
        shown = pv.Show(calc, view)
        shown.Representation = "Surface With Edges" if spec["edges"] else "Surface"
        shown.EdgeColor = [0.2, 0.2, 0.2]
        pv.ColorBy(shown, ("CELLS" if cells else "POINTS", "field"))
        lut = pv.GetColorTransferFunction("field")
        lut.ApplyPreset("Turbo", True)
        lo, hi = spec["range"]
        lut.RescaleTransferFunction(lo, hi if hi > lo else lo + max(abs(lo), 1.0))
        lut.AutomaticRescaleRangeMode = "Never"
        bar = pv.GetScalarBar(lut, view)
        bar.Title, bar.ComponentTitle = spec["label"], ""
        bar.TitleColor = bar.LabelColor = [0, 0, 0]
        bar.TitleFontSize, bar.LabelFontSize, bar.ScalarBarLength = 20, 18, 0.6
        shown.SetScalarBarVisibility(view, True)
        if p["contacts"]:
            cps = pv.Show(pv.XDMFReader(FileNames=[p["contacts"]]), view)
            cps.Representation, cps.PointSize, cps.AmbientColor = "Points", 2, [0, 0, 0]
            cps.DiffuseColor = [0, 0, 0]
            pv.ColorBy(cps, None)
        view.CameraPosition, view.CameraViewUp = spec["camera"], spec["up"]
        view.CameraFocalPoint = [0, 0, 0]
        view.ResetCamera()
        pv.SaveScreenshot(p["png"], view)
    with open(spec["result"], "w") as f:
        json.dump(ranges, f)


def main(argv):
    if {"-h", "--help"} & set(argv):
        print(__doc__.strip())
        return 0
    ap = argparse.ArgumentParser(prog="plot_fields.py", add_help=False,
                                 usage=__doc__.split("\n\n")[1].replace("usage: ", ""))
    ap.add_argument("dirs", nargs="+", metavar="OUTDIR")
    ap.add_argument("--field", default="pressure")
    ap.add_argument("--times", nargs="+", type=float, default=None)
    ap.add_argument("--edges", action="store_true")
    ap.add_argument("--contacts", action="store_true")
    ap.add_argument("--mirror", action="store_true")
    ap.add_argument("--camera", nargs=3, type=float, default=[1, 0.8, 1.6])
    ap.add_argument("--up", nargs=3, type=float, default=[0, 1, 0])
    ap.add_argument("--out")
    args = ap.parse_args(argv)
    try:
        if len(args.dirs) > 2:
            raise UsageError("OUTDIR: one or two output directories")
        runs = [Run(d) for d in args.dirs]
        if len({r.dim for r in runs}) > 1:
            raise UsageError("OUTDIR2: a run of another dimension than OUTDIR")
        dim = runs[0].dim
        if dim == 1:
            raise UsageError("OUTDIR: a 1D run (plot its gauges: scripts/plot_gauges.py)")
        if dim == 3 and shutil.which("pvbatch") is None:
            raise UsageError("OUTDIR: a 3D run needs ParaView's pvbatch (Debian: paraview "
                             "python3-paraview)")
        if args.mirror and dim != 2:
            raise UsageError("--mirror: 2D runs only")
        if args.contacts and all(r.contacts is None for r in runs):
            raise UsageError("--contacts: no contacts.h5 in " + " or ".join(args.dirs)
                             + " (the deck has no contact)")
        centre, getter = field_of(runs, args.field)
        rows = select(runs, args.times)
    except UsageError as e:
        print(f"plot_fields: error: {e}", file=sys.stderr)
        return 2
    args.out = args.out or os.path.join(args.dirs[0], f"fields_{args.field}.png")
    signs = {mirror_sign(args.field, *s) for s in (MIRRORS if args.mirror else MIRRORS[:1])}
    vmin, vmax = field_range(runs, rows, getter, sorted(signs))
    if dim == 2:
        fig = figure_2d(runs, rows, args.field, (vmin, vmax), args.edges, args.contacts,
                        args.mirror)
        fig.savefig(args.out, dpi=150)
    else:
        plot_3d(runs, rows, args.field, centre, vmin, vmax, args)
    print(f"plot_fields: wrote {args.out} field {args.field} range {vmin!r} {vmax!r}")
    return 0


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--pvbatch":
        pvbatch_main(sys.argv[2])
    else:
        sys.exit(main(sys.argv[1:]))
