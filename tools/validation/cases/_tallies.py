"""Shared by the hidden-effect tally cases (a helper, not a case: its name starts with "_"):
the statistical bound that a tally of clean sets can state."""
from math import comb


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


def detection_agreement(v, tool, prefix, family, effects, ratios, first_seed, clean_first_seed,
                        plus_only):
    """A hidden-effect sweep's named fractions at several noise ratios (10 seeds per size) and
    the detection limits (20 replicates) of 4 clean sets, through `tool(v, env)`, which runs a
    test binary's correlated sweep whose environment keys start with `prefix` (KNEESIM_KW_...).
    Writes per effect the tallies {effect}_{ratio}, the onset, the mean reported limit (over the
    size parameters and, unless plus_only, both directions), its range and limit / onset."""
    import re
    out = tool(v, {prefix + "EFFECTS": ",".join(effects), prefix + "RATIOS": ",".join(ratios),
                   prefix + "SEEDS": "10", prefix + "FIRST_SEED": str(first_seed)})
    fr = {}
    for eff, ratio, named, n in re.findall(rf"^== {family} (\S+) ratio ([0-9.]+): named (\d+) of (\d+)$", out, re.M):
        fr.setdefault(eff, []).append((float(ratio), int(named) / int(n)))
        v.figure(f"{eff}_{ratio.replace('.', 'p')}", f"{named}/{n}")
    det = tool(v, {prefix + "EFFECTS": "none", prefix + "SEEDS": "4",
                   prefix + "FIRST_SEED": str(clean_first_seed), prefix + "DETECTION": "20"})
    lim = {}
    for eff, d, reached, ratio in re.findall(r"^\s+limit (\S+) \S+?([+-])1: (at|beyond) \S+, signal \S+, ratio ([0-9.]+)", det, re.M):
        if d == "+" or not plus_only:
            lim.setdefault(eff, []).append(float(ratio) if reached == "at" else float("inf"))
    for eff in effects:
        o = onset(sorted(fr.get(eff, [])))
        m = sum(lim[eff]) / len(lim[eff])
        v.figure(f"{eff}_onset", o)
        v.figure(f"{eff}_limit", m)
        v.figure(f"{eff}_limit_lo", min(lim[eff]))
        v.figure(f"{eff}_limit_hi", max(lim[eff]))
        v.figure(f"{eff}_factor", m / o if o > 0 else float("nan"))


def tallies_at_1_2(v, tool, prefix, families, effects, seeds_effect, first_effect, seeds_clean,
                   first_clean):
    """Hidden effects sized to 1.2 times the noise RMS and clean sets, per family, through
    `tool(v, env)` (a test binary's correlated sweep, environment keys starting with `prefix`).
    Writes {family}_{effect} and {family}_none tallies ("named/n"), clean_records,
    false_positives and false_positive_upper95_pct."""
    import re
    clean_none = clean_n = 0
    for effs, seeds, first in ((effects, seeds_effect, first_effect), (["none"], seeds_clean, first_clean)):
        out = tool(v, {prefix + "FAMILIES": ",".join(families), prefix + "EFFECTS": ",".join(effs),
                       prefix + "RATIOS": "1.2", prefix + "SEEDS": str(seeds), prefix + "FIRST_SEED": str(first)})
        for fam, eff, named, n in re.findall(r"^== (\S+) (\S+) ratio [0-9.]+: named (\d+) of (\d+)$", out, re.M):
            v.figure(f"{fam}_{eff}", f"{named}/{n}")
            if eff == "none":
                clean_none, clean_n = clean_none + int(named), clean_n + int(n)
    v.figure("clean_records", clean_n)
    v.figure("false_positives", clean_n - clean_none)
    v.figure("false_positive_upper95_pct", 100 * false_positive_upper95(clean_n - clean_none, clean_n), "%")


def sweep_tool(binary, testcase, appended=None, source_dir=False):
    """The `tool(v, env)` of a case: runs a skipped sweep test case of a test binary of the
    build (`binary`, e.g. tests/diagnosis/test_diagnosis_long) with the environment `env` plus
    `appended`, and records the command as it is typed (the environment, then the binary).
    source_dir: the run also gets KNEESIM_SOURCE_DIR (not recorded: validate runs it for you)."""
    def tool(v, env):
        env = dict(env, **(appended or {}))
        rec = " ".join(f"{k}={val}" for k, val in env.items())
        run_env = dict(env, KNEESIM_SOURCE_DIR=v.source) if source_dir else env
        return v.tool(binary, [f"-tc={testcase}", "--no-skip"],
                      record=f'{rec} build/{binary} -tc="{testcase}" --no-skip', env=run_env)
    return tool
