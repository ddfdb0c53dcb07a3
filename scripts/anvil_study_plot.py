"""PNG plots of a parameter study (called by `anvil --study` at its end, or
by hand: python3 anvil_study_plot.py STUDY_DIR [--label VAR=LABEL]...
[--history FILE.csv:COLUMN --scale S --history-label L]).

history.png: the chosen history of every run overlaid (the paper's
figures); summary.png: each summary quantity against the first variable
(one line per value of the others). Needs matplotlib; without it, says so
and exits 3.
"""
import argparse
import csv
import math
import os
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("plots skipped: matplotlib is not installed (Debian: python3-matplotlib)")
    sys.exit(3)

# Quantities that describe the run, not its result.
BOOKKEEPING = {"exit_status", "run_wall_time_s", "wall_time_s", "processes", "elements", "ended_by_criterion",
               "memory_triangulation_bytes", "memory_dof_handler_bytes", "memory_nodal_vectors_bytes",
               "memory_element_state_bytes"}


def number(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return math.nan


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("directory")
    parser.add_argument("--label", action="append", default=[])
    parser.add_argument("--history", default="")
    parser.add_argument("--scale", type=float, default=1.0)
    parser.add_argument("--history-label", default="")
    a = parser.parse_args()

    with open(os.path.join(a.directory, "study.csv")) as f:
        reader = csv.DictReader(f)
        columns = reader.fieldnames
        rows = list(reader)
    labels = dict(item.split("=", 1) for item in a.label)
    variables = [c[:-len("_plot_value")] for c in columns if c.endswith("_plot_value")]
    made = []

    def run_label(row):
        return ", ".join(f"{labels.get(v, v)} = {number(row[v + '_plot_value']):g}" for v in variables)

    if a.history:
        file, column = a.history.rsplit(":", 1)
        fig, ax = plt.subplots(figsize=(7, 4.2))
        for row in rows:
            path = os.path.join(a.directory, row["run"], file)
            if not os.path.exists(path):
                continue
            with open(path) as f:
                h = list(csv.DictReader(f))
            if not h or column not in h[0]:
                continue
            ax.plot([1e3 * float(r["time"]) for r in h], [a.scale * float(r[column]) for r in h],
                    label=run_label(row))
        ax.set_xlabel("time (ms)")
        ax.set_ylabel(a.history_label or f"{file}: {column}")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(a.directory, "history.png"), dpi=110)
        plt.close(fig)
        made.append("history.png")

    first = variables[0]
    start = columns.index(variables[-1] + "_plot_value") + 1
    quantities = [q for q in columns[start:] if q not in BOOKKEEPING and
                  any(not math.isnan(number(r[q])) for r in rows)]
    if quantities:
        n = len(quantities)
        ncols = 3
        nrows = (n + ncols - 1) // ncols
        fig, axes = plt.subplots(nrows, ncols, figsize=(4.2 * ncols, 3.0 * nrows), squeeze=False)
        groups = {}
        for row in rows:
            key = tuple(f"{number(row[v + '_plot_value']):g}" for v in variables[1:])
            groups.setdefault(key, []).append(row)
        for i, q in enumerate(quantities):
            ax = axes[i // ncols][i % ncols]
            for key, group in groups.items():
                group = sorted(group, key=lambda r: number(r[first + "_plot_value"]))
                ax.plot([number(r[first + "_plot_value"]) for r in group], [number(r[q]) for r in group],
                        "o-", label=", ".join(f"{labels.get(v, v)} = {k}" for v, k in zip(variables[1:], key)))
            ax.set_title(q, fontsize=9)
            ax.set_xlabel(labels.get(first, first), fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(True, alpha=0.3)
            if len(groups) > 1 and i == 0:
                ax.legend(fontsize=7)
        for j in range(n, nrows * ncols):
            axes[j // ncols][j % ncols].axis("off")
        fig.tight_layout()
        fig.savefig(os.path.join(a.directory, "summary.png"), dpi=100)
        plt.close(fig)
        made.append("summary.png")
    print("plots: " + ", ".join(made))


if __name__ == "__main__":
    main()
