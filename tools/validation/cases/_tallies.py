"""Shared by the hidden-effect tally cases (a helper, not a case: its name starts with "_"):
running a test binary's sweep (sweep_tool), reading its tally lines, the statistics of the
tallies (the false-positive bound of clean sets, the onset, the logistic onset) and the
agreement of reported detection limits with the onset."""
import os
import random
import re
import statistics
from math import comb, exp, log


def false_positive_upper95(false_positives, records):
    """One-sided 95 % upper bound (Clopper-Pearson) of a false-positive rate seen as
    false_positives of records: the rate at which seeing so few has probability 0.05
    (0 of 60 -> 4.9 %, 1 of 60 -> 7.7 %)."""
    if false_positives >= records:
        return 1.0
    lo, hi = false_positives / records, 1.0
    for _ in range(100):  # bisection on P(X <= fp | p) = 0.05, decreasing in p
        p = 0.5 * (lo + hi)
        cdf = sum(comb(records, k) * p ** k * (1 - p) ** (records - k) for k in range(false_positives + 1))
        lo, hi = (p, hi) if cdf > 0.05 else (lo, p)
    return 0.5 * (lo + hi)



def tally_lines(out):
    """The "== FAMILY EFFECT ratio R: named K of N" lines of a sweep's output `out`, as
    (family, effect, ratio text, named, n) in order."""
    return [(fam, eff, ratio, int(named), int(n)) for fam, eff, ratio, named, n in
            re.findall(r"^== (\S+) (\S+) ratio ([0-9.]+): named (\d+) of (\d+)$", out, re.M)]


def onset(fractions):
    """The ratio at which the named fraction first reaches 0.8 (linear between sizes), from
    (ratio, fraction) pairs in increasing ratio."""
    prev = None
    for r, f in fractions:
        if f >= 0.8:
            if prev is None or prev[1] >= 0.8:
                return r
            return prev[0] + (0.8 - prev[1]) / (f - prev[1]) * (r - prev[0])
        prev = (r, f)
    return float("nan")


def clean_limits(det, plus_only):
    """The reported detection limits of clean sets in a sweep's output `det`, per candidate, as
    the limit's identifiable signal over the clean set's own noise RMS (the generator's noise in
    the diagnosis' RMSE measure, the same measure as the hidden effects' ratios; the limit's
    printed ratio is over the *fitted* error model's RMS, which differs from it when the
    generator is not the error model). A limit beyond the searched sizes counts as infinite."""
    lim, noise = {}, None
    for line in det.splitlines():
        m = re.match(r"^\S+ none ratio \S+ seed \d+.*? noise ([0-9.]+) signal", line)
        if m:
            noise = float(m.group(1))
            continue
        m = re.match(r"^\s+limit (\S+) \S+?([+-])1: (at|beyond) \S+, signal ([0-9.]+),", line)
        if m and (m.group(2) == "+" or not plus_only):
            lim.setdefault(m.group(1), []).append(
                float(m.group(4)) / noise if m.group(3) == "at" else float("inf"))
    return lim


def detection_agreement(v, tool, prefix, family, effects, ratios, first_seed, clean_first_seed,
                        plus_only):
    """A hidden-effect sweep's named fractions at several noise ratios (10 seeds per size) and
    the detection limits (20 replicates) of 4 clean sets, through `tool(v, env)`, which runs a
    test binary's correlated sweep whose environment keys start with `prefix` (KNEESIM_KW_...).
    Writes per effect the tallies {effect}_{ratio}, the onset, the mean reported limit (over the
    size parameters and, unless plus_only, both directions; clean_limits), its range and
    limit / onset."""
    out = tool(v, {prefix + "EFFECTS": ",".join(effects), prefix + "RATIOS": ",".join(ratios),
                   prefix + "SEEDS": "10", prefix + "FIRST_SEED": str(first_seed)})
    fr = {}
    for fam, eff, ratio, named, n in tally_lines(out):
        if fam == family:
            fr.setdefault(eff, []).append((float(ratio), named / n))
            v.figure(f"{eff}_{ratio.replace('.', 'p')}", f"{named}/{n}")
    det = tool(v, {prefix + "EFFECTS": "none", prefix + "SEEDS": "4",
                   prefix + "FIRST_SEED": str(clean_first_seed), prefix + "DETECTION": "20"})
    lim = clean_limits(det, plus_only)
    for eff in effects:
        o = onset(sorted(fr.get(eff, [])))
        m = sum(lim[eff]) / len(lim[eff])
        v.figure(f"{eff}_onset", o)
        v.figure(f"{eff}_limit", m)
        v.figure(f"{eff}_limit_lo", min(lim[eff]))
        v.figure(f"{eff}_limit_hi", max(lim[eff]))
        v.figure(f"{eff}_factor", m / o if o > 0 else float("nan"))


def logistic_x80(x, named):
    """The size x (> 0) at which a logistic curve in ln x, fitted by maximum likelihood to
    (x, named 0/1) pairs, gives an 80 % chance of naming; nan without both outcomes."""
    z = [log(t) for t in x]
    if min(named) == max(named):
        return float("nan")
    b0 = b1 = 0.0
    ridge = 1e-6  # keeps separable data finite
    for _ in range(200):  # Newton on the two coefficients
        g0 = g1 = h00 = h01 = h11 = 0.0
        for zi, yi in zip(z, named):
            p = 1.0 / (1.0 + exp(-max(-700.0, min(700.0, b0 + b1 * zi))))
            g0 += yi - p
            g1 += (yi - p) * zi
            w = p * (1.0 - p)
            h00 += w
            h01 += w * zi
            h11 += w * zi * zi
        g0, g1, h00, h11 = g0 - ridge * b0, g1 - ridge * b1, h00 + ridge, h11 + ridge
        det = h00 * h11 - h01 * h01
        d0, d1 = (h11 * g0 - h01 * g1) / det, (h00 * g1 - h01 * g0) / det
        b0, b1 = b0 + d0, b1 + d1
        if max(abs(d0), abs(d1)) < 1e-10:
            break
    if not b1 > 0:
        return float("nan")
    return exp((log(4.0) - b0) / b1)


def twin_agreement(v, tool, prefix, family, effects, ratios, first_seed, seeds):
    """Each hidden-effect set against the detection limit reported for its clean twin (the
    same noise draw and scale without the effect; the sweep's {prefix}TWIN_DETECTION, 20
    replicates): x = the set's identifiable signal / the twin's limit signal (in the direction
    the hidden effect takes; the mean over the parameters it changes). A limit beyond the
    searched sizes enters with the signal at the searched end, a lower bound: such a set's x is
    too large, which can only move x80 up (towards "optimistic"). Writes per effect the named
    tallies per ratio, the x at which a logistic fit in ln x names 80 % (x80: 1 if the limits
    are exact; above 1 they are optimistic), its 95 % bootstrap interval (1000 resamples of the
    sets), the named fraction for x below 1 and at or above 1, and the twins named other than
    none."""
    out = tool(v, {prefix + "EFFECTS": ",".join(effects), prefix + "RATIOS": ",".join(ratios),
                   prefix + "SEEDS": str(seeds), prefix + "FIRST_SEED": str(first_seed),
                   prefix + "TWIN_DETECTION": "20"})
    for fam, eff, ratio, named, n in tally_lines(out):
        if fam == family:
            v.figure(f"{eff}_{ratio.replace('.', 'p')}", f"{named}/{n}")
    sets, cur, twin_named = {}, None, 0
    for line in out.splitlines():
        m = re.match(rf"^{family} (\S+) ratio \S+ seed \d+((?: \S+=\S+)*) noise \S+ signal ([0-9.]+).*?: named (\S+) \|", line)
        if m:
            hidden = dict((k, float(val)) for k, val in re.findall(r"(\S+)=(\S+)", m.group(2)))
            cur = {"eff": m.group(1), "signal": float(m.group(3)), "named": m.group(4) == m.group(1),
                   "hidden": hidden, "lim": []}
            sets.setdefault(cur["eff"], []).append(cur)
            continue
        m = re.match(r"^\s+twin noise \S+: named (\S+)", line)
        if m:
            twin_named += m.group(1) != "none"
            continue
        m = re.match(r"^\s+twin limit (\S+) (\S+?)([+-])1: (at|beyond) \S+, signal ([0-9.]+),.*null (\S+)$", line)
        if m and cur is not None and m.group(1) == cur["eff"] and m.group(2) in cur["hidden"]:
            # the limit in the direction the hidden effect takes, for each parameter it changes
            if (cur["hidden"][m.group(2)] > float(m.group(6))) == (m.group(3) == "+"):
                cur["lim"].append(float(m.group(5)))
    rng = random.Random(20261129)
    for eff in effects:
        xs = [s["signal"] * len(s["lim"]) / sum(s["lim"]) for s in sets[eff]]
        ys = [1.0 if s["named"] else 0.0 for s in sets[eff]]
        boot = []
        for _ in range(1000):
            k = [rng.randrange(len(xs)) for _ in xs]
            b = logistic_x80([xs[i] for i in k], [ys[i] for i in k])
            if b == b:
                boot.append(b)
        cuts = statistics.quantiles(boot, n=40, method="inclusive")  # 2.5 % steps
        v.figure(f"{eff}_x80", logistic_x80(xs, ys))
        v.figure(f"{eff}_x80_lo", cuts[0])
        v.figure(f"{eff}_x80_hi", cuts[-1])
        below = [y for x, y in zip(xs, ys) if x < 1.0]
        above = [y for x, y in zip(xs, ys) if x >= 1.0]
        v.figure(f"{eff}_below", f"{int(sum(below))}/{len(below)}")
        v.figure(f"{eff}_above", f"{int(sum(above))}/{len(above)}")
    v.figure("twins", sum(len(s) for s in sets.values()))
    v.figure("twins_named", twin_named)


def tallies_at_1_2(v, tool, prefix, families, effects, seeds_effect, first_effect, seeds_clean,
                   first_clean):
    """Hidden effects sized to 1.2 times the noise RMS and clean sets, per family, through
    `tool(v, env)` (a test binary's correlated sweep, environment keys starting with `prefix`).
    Writes {family}_{effect} and {family}_none tallies ("named/n"), clean_records,
    false_positives and false_positive_upper95_pct."""
    clean_none = clean_n = 0
    for effs, seeds, first in ((effects, seeds_effect, first_effect), (["none"], seeds_clean, first_clean)):
        out = tool(v, {prefix + "FAMILIES": ",".join(families), prefix + "EFFECTS": ",".join(effs),
                       prefix + "RATIOS": "1.2", prefix + "SEEDS": str(seeds), prefix + "FIRST_SEED": str(first)})
        for fam, eff, _, named, n in tally_lines(out):
            v.figure(f"{fam}_{eff}", f"{named}/{n}")
            if eff == "none":
                clean_none, clean_n = clean_none + named, clean_n + n
    v.figure("clean_records", clean_n)
    v.figure("false_positives", clean_n - clean_none)
    v.figure("false_positive_upper95_pct", 100 * false_positive_upper95(clean_n - clean_none, clean_n), "%")


def sweep_tool(binary, testcase, appended=None, source_dir=False):
    """The `tool(v, env)` of a case: runs a skipped sweep test case of a test binary of the
    build (`binary`, e.g. tests/diagnosis/test_diagnosis_long) with the environment `env` plus
    `appended`, and records the command as it is typed (the environment, then the binary).
    source_dir: the run also gets KNEESIM_SOURCE_DIR (not recorded: validate runs it for you).
    Each run's output (every set's fit, every limit) is kept in the case's folder as
    sweep_<n>.txt, headed by its command, for a reader to audit the tallies."""
    def tool(v, env):
        env = dict(env, **(appended or {}))
        rec = " ".join(f"{k}={val}" for k, val in env.items())
        run_env = dict(env, KNEESIM_SOURCE_DIR=v.source) if source_dir else env
        command = f'{rec} build/{binary} -tc="{testcase}" --no-skip'
        out = v.tool(binary, [f"-tc={testcase}", "--no-skip"], record=command, env=run_env)
        v.sweeps = getattr(v, "sweeps", 0) + 1  # numbered per validate run, overwritten by the next
        n = v.sweeps
        with open(os.path.join(v.dir, f"sweep_{n}.txt"), "w") as f:
            f.write(f"# {command}\n{out}")
        return out
    return tool
