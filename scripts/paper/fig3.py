#!/usr/bin/python3
"""The paper's Figs. 3 and 4: a cylindrical detonation of TNT in one block (left) and in an
imbricate brick mesh tied by sticky joints (right).

usage: /usr/bin/python3 scripts/paper/fig3.py [--force] [--times T ...] [--decks MONO IMB]

Runs inputs/paper/fig3_detonation_{monolithic,imbricate}.yaml (or the two decks of --decks)
through scpdyn (one thread) into out/paper/fig3/<deck>/ when their outputs are missing
(--force: always), and draws with scripts/plot_fields.py, the quarter model mirrored about its
symmetry planes in Fig. 4 so that the ignition point is in the middle:
  out/paper/fig3_meshes.png    Fig. 3: the deformed meshes, the joints' contact points as dots
  out/paper/fig4_pressure.png  Fig. 4: the pressure, one colour scale, joints as dots
at the frames nearest --times (s; default 1, 3 and 5 us), a row per time. Prints the pressure
range drawn and E2 of the imbricate run's gauge pressures against the monolithic run's over
the whole run (verification.md 0.3): the sticky joints should leave the detonation unchanged.
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))
import paper_util as pu  # noqa: E402
import plot_fields as pf  # noqa: E402

DECKS = ["fig3_detonation_monolithic", "fig3_detonation_imbricate"]
NAMES = ["monolithic", "imbricate, sticky joints"]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--force", action="store_true", help="rerun the decks")
    ap.add_argument("--times", nargs="+", type=float, default=[1e-6, 3e-6, 5e-6], metavar="T",
                    help="times of the rows, s")
    ap.add_argument("--decks", nargs=2, metavar=("MONO", "IMB"),
                    default=[pu.deck_path(d) for d in DECKS], help="two other decks")
    args = ap.parse_args()
    runs, summaries = [], []
    for deck, name in zip(args.decks, NAMES):
        if not os.path.exists(deck):
            sys.exit(f"fig3.py: no deck '{deck}'")
        out = os.path.join(pu.OUT, "fig3", os.path.splitext(os.path.basename(deck))[0])
        summaries.append(pu.run(deck, out, force=args.force))
        run = pf.Run(out)
        run.name = name + (" (stopped)" if pu.failed(summaries[-1]) else "")
        runs.append(run)
    try:
        rows = pf.select(runs, args.times)
    except pf.UsageError as e:
        sys.exit(f"fig3.py: {e}")

    # the meshes of the quarter only: mirrored, 200 cells across a panel merge into grey
    fig = pf.figure_2d(runs, rows, None, contacts=True, width=4.5)
    fig.suptitle("Fig. 3: deformed meshes (the quarter model, lit at the origin), contact "
                 "points of the joints as red dots", fontsize=10)
    pu.save_figure(fig, "fig3_meshes")
    _, getter = pf.field_of(runs, "pressure")
    vrange = pf.field_range(runs, rows, getter)
    fig = pf.figure_2d(runs, rows, "pressure", vrange, contacts=True, mirror=True, width=4.5)
    fig.suptitle("Fig. 4: pressure (the quarter model mirrored about x = 0 and y = 0), "
                 "contact points of the joints as white dots", fontsize=10)
    pu.save_figure(fig, "fig4_pressure")
    print(f"pressure drawn: {vrange[0] * 1e-9:.3f} to {vrange[1] * 1e-9:.3f} GPa")

    mono, imb = (pu.gauges(r.dir) for r in runs)
    keys = [k for k in mono if k.endswith(":pressure") and k in imb]
    window = (0.0, min(s["end_time"] for s in summaries))
    e2 = None if any(pu.failed(s) for s in summaries) else pu.e2_norm(
        [(imb["time"], imb[k]) for k in keys], [(mono["time"], mono[k]) for k in keys], window)
    print(f"gauge pressure E2, imbricate against monolithic, {len(keys)} gauges over "
          f"0-{window[1] * 1e6:.2f} us: " + ("- (a run stopped)" if e2 is None else f"{e2:.2e}"))
    for r, s in zip(runs, summaries):
        print(f"{r.name}: {s.get('status')}, {pu.cost(s)}")


if __name__ == "__main__":
    main()
