#!/usr/bin/env python3
"""A semicircular arch's spreading capacity against its thickness, by PRD and by the DEM.

The arch (the circular-arch generator: radius 1 m, 20 voussoirs, the right support moving
outward) is generated at each thickness, run by both methods through `import masonry`, and its
capacity (m of support spreading) plotted against t/R. Below t/R = 0.1075 (Milankovitch 1907)
the arch does not stand, so the capacity falls to 0 there.

    PYTHONPATH=build/python python3 examples/python/thickness.py [--no-dem] [--dem-step 0.004] [--out thickness.png]

The DEM runs at a coarser increment than PRD by default (--dem-step, 4 mm; its collapse is still
bracketed to 1% of the increment): about 30 s for the six arches on one core of the 2-core
reference machine, PRD a few milliseconds each; --no-dem runs PRD alone. The figure needs matplotlib (Debian's python3-matplotlib); without it the table is
printed and the figure skipped with a message.
"""

import argparse
import sys

import masonry


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--thickness", type=float, nargs="+", default=[0.11, 0.12, 0.13, 0.14, 0.155, 0.17],
                    help="thicknesses t, m (radius 1 m)")
    ap.add_argument("--voussoirs", type=int, default=20)
    ap.add_argument("--no-dem", action="store_true", help="PRD alone")
    ap.add_argument("--dem-step", type=float, default=0.004, help="the DEM's increment of d, m (PRD: 1 mm)")
    ap.add_argument("--out", default="thickness.png", help="the figure (PNG, SVG or PDF, by its extension)")
    a = ap.parse_args()

    rows = []
    for t in a.thickness:
        case = masonry.generate("circular-arch", radius=1.0, thickness=t, voussoirs=a.voussoirs)
        prd = masonry.run_prd(case)
        dem = None if a.no_dem else masonry.run_dem(case, step=a.dem_step)
        rows.append((t, prd, dem))
        print(f"t = {t:.3f} m: PRD {prd.capacity * 1e3:7.2f} mm ({prd.status})"
              + ("" if dem is None else f", DEM {dem.capacity * 1e3:7.2f} mm ({dem.status}, {dem.time_s:.1f} s)"),
              flush=True)

    print("\n  t/R   PRD capacity [mm]" + ("" if a.no_dem else "   DEM capacity [mm]"))
    for t, prd, dem in rows:
        print(f"{t:6.3f}  {prd.capacity * 1e3:18.2f}" + ("" if dem is None else f"  {dem.capacity * 1e3:18.2f}"))

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("\nmatplotlib is not installed (Debian: apt-get install python3-matplotlib): no figure, the table above is the result.")
        return 0
    fig, ax = plt.subplots(figsize=(6, 4))
    ts = [t for t, _, _ in rows]
    ax.plot(ts, [p.capacity * 1e3 for _, p, _ in rows], "o-", label="PRD")
    if not a.no_dem:
        ax.plot(ts, [d.capacity * 1e3 for _, _, d in rows], "s--", label=f"DEM (increment {a.dem_step * 1e3:g} mm)")
    ax.axvline(0.1075, color="grey", lw=0.8, ls=":", label="Milankovitch t/R = 0.1075")
    ax.set_xlabel("thickness t/R")
    ax.set_ylabel("spreading capacity [mm]")
    ax.set_title(f"Semicircular arch, R = 1 m, {a.voussoirs} voussoirs")
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.out)
    print(f"\nwrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
