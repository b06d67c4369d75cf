"""Tables of the convergence report: per-seed rows, means and standard deviations over seeds,
fitted convergence rates, the ranking at the largest budget, and the Markdown page."""
import csv
import math
import os

RUN_FIELDS = ["scene", "config", "integrator", "args", "budget_kind", "budget", "seed", "seconds", "spp",
              "rmse", "relmse"]
SUMMARY_FIELDS = ["scene", "config", "budget_kind", "budget", "seeds", "seconds_mean", "spp_mean", "rmse_mean",
                  "rmse_std", "relmse_mean", "relmse_std"]


def _mean_std(values):
    m = sum(values) / len(values)
    s = math.sqrt(sum((v - m) ** 2 for v in values) / (len(values) - 1)) if len(values) > 1 else 0.0
    return m, s


def summarise(runs):
    """{scene: {config: [row per budget, ascending]}} with means and sample standard deviations over seeds."""
    groups = {}
    for r in runs:
        groups.setdefault((r["scene"], r["config"], r["budget"]), []).append(r)
    out = {}
    for (scene, config, budget), rows in groups.items():
        row = {"scene": scene, "config": config, "budget_kind": rows[0]["budget_kind"], "budget": budget,
               "seeds": len(rows)}
        for key in ("seconds", "spp", "rmse", "relmse"):
            row[key + "_mean"], row[key + "_std"] = _mean_std([r[key] for r in rows])
        out.setdefault(scene, {}).setdefault(config, []).append(row)
    for configs in out.values():
        for rows in configs.values():
            rows.sort(key=lambda r: r["budget"])
    return out


def slope(rows):
    """Least-squares slope of log relMSE against log time (-1 for an unbiased estimator at a fixed
    cost per sample); None with fewer than two budgets."""
    pts = [(math.log(r["seconds_mean"]), math.log(r["relmse_mean"])) for r in rows
           if r["seconds_mean"] > 0 and r["relmse_mean"] > 0]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx > 0 else None


def ranking(configs):
    """At the largest budget: [(label, last row, relMSE / best relMSE, efficiency ratio, slope)], best first.
    Efficiency is 1 / (relMSE · time), so it compares configurations whose times differ."""
    last = {label: rows[-1] for label, rows in configs.items()}
    best = min(r["relmse_mean"] for r in last.values())
    best_eff = max(1.0 / (r["relmse_mean"] * r["seconds_mean"]) for r in last.values())
    out = [(label, r, r["relmse_mean"] / best, best_eff * r["relmse_mean"] * r["seconds_mean"], slope(configs[label]))
           for label, r in last.items()]
    return sorted(out, key=lambda t: t[1]["relmse_mean"])


def comparison(runs, scene, combination, part):
    """Per budget (ascending): (budget, [relMSE_part / relMSE_combination per seed],
    [efficiency factor (relMSE · time)_part / (relMSE · time)_combination per seed]); seeds paired."""
    by = {}
    for r in runs:
        if r["scene"] == scene and r["config"] in (combination, part):
            by[(r["config"], r["budget"], r["seed"])] = r
    out = []
    for budget in sorted({k[1] for k in by}):
        ratio, eff = [], []
        for seed in sorted({k[2] for k in by if k[1] == budget}):
            c, q = by.get((combination, budget, seed)), by.get((part, budget, seed))
            if c and q and c["relmse"] > 0 and c["seconds"] > 0:
                ratio.append(q["relmse"] / c["relmse"])
                eff.append(q["relmse"] * q["seconds"] / (c["relmse"] * c["seconds"]))
        out.append((budget, ratio, eff))
    return out


def _ms(values):
    if not values:
        return "–"
    m, s = _mean_std(values)
    return f"{m:.3g} ± {s:.2g}"


def _comparison_lines(runs, scene, comparisons, budget_kind):
    unit = "s" if budget_kind == "time" else "spp"
    lines = []
    for comp in comparisons:
        rows = {part: comparison(runs, scene, comp["combination"], part) for part in comp["parts"]}
        budgets = [b for b, _, _ in next(iter(rows.values()))]
        lines += [f"**{comp['combination']}** against its parts: factor by which each part's relMSE · time exceeds "
                  f"the combination's (> 1: the combination wins at equal time), per seed (same seed, same budget), "
                  "mean ± sd over seeds; last column: the plain relMSE ratio at the largest budget.", "",
                  "| part | " + " | ".join(f"{b:g} {unit}" for b in budgets) + " | relMSE ratio, largest |",
                  "|---|" + "---|" * (len(budgets) + 1)]
        for part, per in rows.items():
            lines.append(f"| {part} | " + " | ".join(_ms(eff) for _, _, eff in per) + f" | {_ms(per[-1][1])} |")
        lines.append("")
    return lines


def comparison_summary(runs, scene, comp):
    """One sentence: the efficiency factor against each part at the largest budget."""
    parts = []
    for part in comp["parts"]:
        _, _, eff = comparison(runs, scene, comp["combination"], part)[-1]
        if eff:
            m, s = _mean_std(eff)
            parts.append(f"{part} ×{m:.2g} ± {s:.1g}")
    return f"{comp['combination']} against its parts (relMSE · time ÷ the combination's, largest budget): " + \
        ", ".join(parts)


def write_csv(path, fields, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore", lineterminator="\n")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def _table(configs, budget_kind):
    unit = "s" if budget_kind == "time" else "spp"
    lines = [f"| configuration | budget ({unit}) | time (s) | spp | relMSE (mean ± sd) | RMSE (mean ± sd) | "
             f"relMSE ÷ best | efficiency: best ÷ this | slope |",
             "|---|---|---|---|---|---|---|---|---|"]
    for label, r, ratio, eff, s in ranking(configs):
        lines.append(f"| {label} | {r['budget']:g} | {r['seconds_mean']:.2f} | {r['spp_mean']:.0f} | "
                     f"{r['relmse_mean']:.3g} ± {r['relmse_std']:.2g} | {r['rmse_mean']:.3g} ± {r['rmse_std']:.2g} | "
                     f"{ratio:.2f} | {eff:.2f} | {'' if s is None else f'{s:.2f}'} |")
    return "\n".join(lines)


def markdown(cfg, scenes, summary, command, runtime, machine, date, runs=()):
    """The report page; `scenes` is a list of dicts with name, note, scene, reference stats and figure names."""
    b = cfg["budget"]
    mode = "**preliminary (quick) budgets**" if cfg["quick"] else "full budgets"
    full = (f"The full report is the same command without `--quick` (budgets ×{1 / cfg['quick_budget_scale']:g}, "
            "full resolution, all seeds, longer references)." if cfg["quick"] else "")
    out = [f"# Convergence report", "",
           cfg["description"], "",
           f"Generated {date} on {machine} in {runtime / 60:.1f} min with {mode}:", "",
           f"    {command}", "", full, "",
           f"Budgets: {'equal time, --time' if b['kind'] == 'time' else 'equal samples, --spp'} "
           f"{', '.join(f'{v:g}' for v in b['values'])}; seeds {', '.join(str(s) for s in cfg['seeds'])}; "
           f"reference: {cfg['reference']['time']:g} s of `{' '.join([cfg['reference']['integrator']] + cfg['reference']['args'])}` "
           "unless a scene says otherwise. Errors are over X, Y, Z of every pixel against the reference "
           "(`kasha metrics`: relMSE = mean (x − ref)² / (ref² + 0.01)); the reference's own noise is part of them, "
           "so they level off where it dominates. Times are the renders' own (statistics JSON), on a machine that may "
           "be shared, so equal-time points scatter in time.", "",
           "Data: [runs.csv](runs.csv) (one row per render), [summary.csv](summary.csv) (mean and standard deviation "
           "over seeds). In the tables, *slope* is the fitted log-log slope of relMSE against time (−1 for an "
           "unbiased estimator), *relMSE ÷ best* compares at the largest budget, and *efficiency* is 1 / (relMSE · "
           "time), best ÷ this (the factor of time this configuration needs to match the best).", ""]
    out += ["## Summary", "", "At the largest budget, by mean relMSE over seeds (factor: relMSE ÷ the best's):", ""]
    for s in scenes:
        ranked = ranking(summary[s["name"]])
        rest = ", ".join(f"{label} ×{ratio:.2g}" for label, _, ratio, _, _ in ranked[1:])
        out.append(f"- **{s['name']}**: {ranked[0][0]} best; then {rest}.")
        for comp in s.get("comparisons", []):
            out.append(f"  {comparison_summary(runs, s['name'], comp)} ({len(cfg['seeds'])} seeds).")
    out.append("")
    for s in scenes:
        rs = s["reference_stats"]
        out += [f"## {s['name']}", "", f"`{os.path.relpath(s['scene'], cfg['repo'])}` at {s['resolution'][0]}×"
                f"{s['resolution'][1]}. {s['note']}", "",
                f"Reference: `{' '.join([s['reference']['integrator']] + s['reference']['args'])}`, "
                f"{rs.get('spp', '?')} spp in {rs.get('seconds', 0):.0f} s.", "",
                _table(summary[s["name"]], b["kind"]), ""]
        out += _comparison_lines(runs, s["name"], s.get("comparisons", []), b["kind"])
        out += [f"![convergence]({s['plot']})", "", f"![crops]({s['crops']})", ""]
    return "\n".join(out) + "\n"
