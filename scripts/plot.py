"""Plots of a cdsim sweep: speed against error, area against error (a sweep run
with --area), the paper's Fig. 8-10 in our terms, and error against every swept
width. Usage: scripts/plot SWEEP_DIR [MORE...]."""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FAMILY_STYLE = {
    "cd-none": ("tab:blue", "o"), "cd-linear": ("tab:orange", "s"), "cd-dense2": ("tab:green", "^"),
    "cd-dense4": ("tab:red", "v"), "cd-dense2-linear": ("tab:purple", "D"), "divide": ("black", "x"),
    "kim-iter": ("tab:brown", "P"), "kim-pipe": ("tab:pink", "*"), "affine-sub16": ("tab:gray", "<"),
    "affine-sub8": ("tab:olive", ">"), "affine": ("tab:cyan", "h"), "cd-persp": ("gold", "d"),
    "quad-sub16": ("darkviolet", "v"), "quad-sub8": ("sienna", "<"), "quad-sub32": ("teal", "^"),
}
NUMERIC = ["pixels", "cycles", "pixels_per_clock", "table_entries", "table_bits",
           "error_mean", "error_rms", "error_p99", "error_max", "footprint_max", "texel_mismatch",
           "over_lsb", "flagged_triangles"]
# Present, and empty unless the sweep ran with --area and the design has RTL.
AREA = ["logic_area_um2", "nand2_eq", "flops", "sram_bits", "sram_area_um2", "flop_table_area_um2",
        "total_area_um2"]


def load(dirs):
    rows, defaults, meta = [], {}, []
    for d in dirs:
        csv_path = os.path.join(d, "sweep.csv")
        if not os.path.exists(csv_path):
            sys.exit(f"plot: {csv_path} does not exist (run: build/cdsim sweep --out {d})")
        with open(os.path.join(d, "sweep.json")) as f:
            j = json.load(f)
        defaults = j.get("defaults", defaults)
        meta.append(f"{j['scene']['name']} ({j['build']})")
        params = list(j["defaults"].keys())
        with open(csv_path) as f:
            for r in csv.DictReader(f):
                for k in NUMERIC:
                    r[k] = float(r[k])
                for k in AREA:
                    r[k] = float(r[k]) if r.get(k) else None
                for p in params:
                    r[p] = int(r[p])
                rows.append(r)
    return rows, defaults, meta


def is_default(row, defaults):
    return all(row[p] == v for p, v in defaults.items())


def pareto(points):
    """Lowest cost (cycles, area) for each error level: points sorted by error, cost falling."""
    front, best = [], math.inf
    for err, cost in sorted(points):
        if cost < best:
            front.append((err, cost))
            best = cost
    return front


def designs_in(rows):
    seen = []
    for r in rows:
        if r["design"] not in seen:
            seen.append(r["design"])
    return seen


def finish(fig, path, caption):
    fig.text(0.01, 0.005, caption, fontsize=6, color="dimgray")
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    fig.savefig(path, dpi=130)
    plt.close(fig)
    print(f"wrote {path}")


def pareto_panel(ax, rows, metric, cost, xlabel, ylabel):
    """Every design's points of cost against `metric`, and its Pareto front, log-log."""
    for d in designs_in(rows):
        color, marker = FAMILY_STYLE.get(d, ("k", "."))
        pts = [(r[metric], cost(r)) for r in rows if r["design"] == d and r[metric] > 0]
        if not pts:
            continue
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], s=14, color=color, marker=marker,
                   alpha=0.5)
        front = pareto(pts)
        ax.plot([p[0] for p in front], [p[1] for p in front], color=color, label=d, lw=1.5,
                drawstyle="steps-post")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)


def speed_vs_error(rows, out, caption):
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.5))
    for ax, metric, label in ((axes[0], "error_mean", "mean error (texels)"),
                              (axes[1], "error_max", "max error (texels)")):
        pareto_panel(ax, rows, metric, lambda r: r["cycles"], label, "cycles (scene total)")
    axes[0].legend(fontsize=7, ncol=2)
    fig.suptitle("Speed against error; lines are each design's Pareto front")
    finish(fig, os.path.join(out, "cycles_vs_error.png"), caption)


def area_vs_error(rows, out, caption):
    """Total area (logic + SRAM table) against mean and footprint-max error with
    each design's Pareto front, and area x cycles per pixel against mean error."""
    rows = [r for r in rows if r["total_area_um2"]]
    if not rows:
        print("plot: no area in these sweeps (cdsim sweep --area): area plots skipped")
        return
    fig, axes = plt.subplots(1, 3, figsize=(18, 5.5))
    panels = ((axes[0], "error_mean", "mean error (texels)", lambda r: r["total_area_um2"],
               "total area (um^2)"),
              (axes[1], "footprint_max", "footprint-max error", lambda r: r["total_area_um2"],
               "total area (um^2)"),
              (axes[2], "error_mean", "mean error (texels)",
               lambda r: r["total_area_um2"] * r["cycles"] / max(1.0, r["pixels"]),
               "total area x cycles per pixel (um^2)"))
    for ax, metric, xlabel, cost, ylabel in panels:
        pareto_panel(ax, rows, metric, cost, xlabel, ylabel)
    axes[0].legend(fontsize=7, ncol=2)
    fig.suptitle("Cost against error (Yosys onto osu018, SRAM table; docs/area.md); "
                 "lines are each design's Pareto front")
    finish(fig, os.path.join(out, "area_vs_error.png"), caption)


def interpolate_log(front, error):
    """Cycles a front needs to reach `error` (log-log interpolation), or None."""
    if not front or error < front[0][0]:
        return None
    for (e0, c0), (e1, c1) in zip(front, front[1:]):
        if e0 <= error <= e1:
            if e1 == e0:
                return c1
            t = (math.log(error) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(c0) + t * (math.log(c1) - math.log(c0)))
    return front[-1][1]


def equal_error_table(rows, defaults, out):
    """Cycles of each design at default widths relative to each Kim-style
    variant's Pareto front at the same mean error; printed and saved as CSV."""
    lines = ["scene,design,mean_error,cycles,table_bits,total_area_um2,reference,reference_cycles,"
             "ratio,reference_area_um2,area_ratio"]
    for scene in sorted({r["scene"] for r in rows}):
        srows = [r for r in rows if r["scene"] == scene]
        for ref in ("kim-iter", "kim-pipe"):
            front = pareto([(r["error_mean"], r["cycles"]) for r in srows if r["design"] == ref])
            area_front = pareto([(r["error_mean"], r["total_area_um2"]) for r in srows
                                 if r["design"] == ref and r["total_area_um2"]])
            for d in designs_in(srows):
                own = [r for r in srows if r["design"] == d and is_default(r, defaults)]
                if d == ref or not own or not front:
                    continue
                need = interpolate_log(front, own[0]["error_mean"])
                area = own[0]["total_area_um2"]
                need_area = interpolate_log(area_front, own[0]["error_mean"])
                lines.append(f"{scene},{d},{own[0]['error_mean']:.4e},{int(own[0]['cycles'])},"
                             f"{int(own[0]['table_bits'])},{f'{area:.0f}' if area else 'n/a'},{ref},"
                             + (f"{need:.0f},{own[0]['cycles'] / need:.3f}" if need else "n/a,n/a") + ","
                             + (f"{need_area:.0f},{area / need_area:.3f}" if area and need_area
                                else "n/a,n/a"))
    path = os.path.join(out, "equal_error.csv")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(l.replace(",", "  ") for l in lines))
    print(f"wrote {path}")


def fig8(rows, defaults, out, caption):
    scenes = sorted({r["scene"] for r in rows})
    designs = [d for d in designs_in(rows) if d != "kim-iter"]
    fig, ax = plt.subplots(figsize=(12, 5))
    width = 0.8 / max(1, len(scenes))
    notes = []
    for si, scene in enumerate(scenes):
        srows = [r for r in rows if r["scene"] == scene]
        # kim-iter's cost to reach a mean error: its front over all swept configurations.
        kim = pareto([(r["error_mean"], r["cycles"]) for r in srows if r["design"] == "kim-iter"])
        ratios = []
        for d in designs:
            own = [r for r in srows if r["design"] == d and is_default(r, defaults)]
            if not own or not kim:
                ratios.append(0)
                continue
            need = interpolate_log(kim, own[0]["error_mean"])
            if need is None:
                ratios.append(0)
                notes.append(f"{scene}/{d}: mean error {own[0]['error_mean']:.2e} is below kim-iter's best")
                continue
            ratios.append(own[0]["cycles"] / need)
        xs = [i + si * width for i in range(len(designs))]
        bars = ax.bar(xs, ratios, width=width, label=scene)
        for b, v in zip(bars, ratios):
            ax.text(b.get_x() + b.get_width() / 2, v, f"{v:.2f}" if v else "n/a", ha="center",
                    va="bottom", fontsize=7)
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xticks([i + width * (len(scenes) - 1) / 2 for i in range(len(designs))])
    ax.set_xticklabels(designs, rotation=30, ha="right")
    ax.set_ylabel("cycles / kim-iter cycles at equal mean error")
    ax.set_title("Fig. 8 in cdsim's terms: each design at default widths against kim-iter's "
                 "Pareto front (1 = as fast as kim-iter)")
    ax.legend(fontsize=8)
    if notes:
        ax.text(0.01, 0.97, "\n".join(notes), transform=ax.transAxes, va="top", fontsize=7)
    finish(fig, os.path.join(out, "fig8_cycles_vs_kim.png"), caption)


def fig9(rows, defaults, out, caption):
    pairs = [("cd-none", "cd-linear"), ("cd-dense2", "cd-dense2-linear")]
    metrics = [("error_mean", "mean"), ("error_p99", "p99"), ("error_max", "max"),
               ("footprint_max", "footprint max"), ("texel_mismatch", "texel mismatch share")]
    fig, axes = plt.subplots(1, len(pairs), figsize=(12, 5))
    for ax, (plain, corrected) in zip(axes, pairs):
        vals = {}
        for d in (plain, corrected):
            own = [r for r in rows if r["design"] == d and is_default(r, defaults)]
            vals[d] = [own[0][m] if own else 0 for m, _ in metrics]
        xs = range(len(metrics))
        ax.bar([x - 0.2 for x in xs], vals[plain], width=0.4, label=f"{plain} (no correction)")
        ax.bar([x + 0.2 for x in xs], vals[corrected], width=0.4, label=f"{corrected} (linear correction)")
        ax.set_yscale("log")
        ax.set_xticks(list(xs))
        ax.set_xticklabels([n for _, n in metrics], rotation=20)
        ax.set_ylabel("texels (share for texel mismatch)")
        ax.legend(fontsize=8)
        ax.grid(True, axis="y", which="both", alpha=0.3)
    fig.suptitle("Fig. 9: error statistics with and without linear correction (default widths)")
    finish(fig, os.path.join(out, "fig9_correction_error.png"), caption)


def fig10(rows, defaults, out, caption):
    methods = ["cd-none", "cd-dense2", "cd-dense4", "cd-linear", "cd-dense2-linear"]
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for d in methods:
        color, marker = FAMILY_STYLE[d]
        pts = [(r["cycles"], r["error_mean"]) for r in rows if r["design"] == d]
        if not pts:
            continue
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], color=color, marker=marker, alpha=0.35, s=14)
        own = [r for r in rows if r["design"] == d and is_default(r, defaults)]
        if own:
            ax.scatter([own[0]["cycles"]], [own[0]["error_mean"]], color=color, marker=marker, s=90,
                       edgecolor="k", label=f"{d} (table {int(own[0]['table_bits'])} bits)")
    ax.set_yscale("log")
    ax.set_xlabel("cycles (scene total)")
    ax.set_ylabel("mean error (texels)")
    ax.set_title("Fig. 10: correction methods, error against cycles\n(large markers: default widths; small: sweep)")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    finish(fig, os.path.join(out, "fig10_correction_methods.png"), caption)


def error_vs_widths(rows, defaults, out, caption):
    swept = sorted({name for r in rows for name in r["swept"].split("+") if name != "-"})
    for p in swept:
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
        for d in designs_in(rows):
            # Rows that vary p and hold every other parameter at its default.
            pts = sorted((r[p], r["error_mean"], r["error_max"]) for r in rows if r["design"] == d
                         and all(r[q] == v for q, v in defaults.items() if q != p))
            if len({x for x, _, _ in pts}) < 2:
                continue
            color, marker = FAMILY_STYLE.get(d, ("k", "."))
            axes[0].plot([x for x, _, _ in pts], [m for _, m, _ in pts], marker=marker, color=color, label=d)
            axes[1].plot([x for x, _, _ in pts], [m for _, _, m in pts], marker=marker, color=color, label=d)
        for ax, label in ((axes[0], "mean error (texels)"), (axes[1], "max error (texels)")):
            ax.set_yscale("log")
            ax.set_xlabel(p)
            ax.set_ylabel(label)
            ax.grid(True, which="both", alpha=0.3)
        axes[0].legend(fontsize=7)
        fig.suptitle(f"Error against {p} (other widths at their defaults)")
        finish(fig, os.path.join(out, f"error_vs_{p}.png"), caption)


def main():
    dirs = sys.argv[1:]
    if not dirs:
        sys.exit("usage: scripts/plot SWEEP_DIR [MORE_SWEEP_DIRS...]")
    rows, defaults, meta = load(dirs)
    if not rows:
        sys.exit("plot: no rows")
    out = dirs[0]
    caption = "sweep of " + "; ".join(meta)
    speed_vs_error(rows, out, caption)
    area_vs_error(rows, out, caption)
    fig8(rows, defaults, out, caption)
    equal_error_table(rows, defaults, out)
    fig9(rows, defaults, out, caption)
    fig10(rows, defaults, out, caption)
    error_vs_widths(rows, defaults, out, caption)


if __name__ == "__main__":
    main()
