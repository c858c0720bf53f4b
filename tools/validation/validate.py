#!/usr/bin/python3
"""kneesim validation runner: runs named cases against the current build, writes each case's
figures to build/validation/<case>.json (named numbers with units), and regenerates or checks
the tables of the documentation that show them.

A case is one file tools/validation/cases/<case>.py (tools/validation/README.md says how to
write one). Its tables live in the Markdown documentation between the markers

    <!-- validate:<case> -->            (or <!-- validate:<case>/<name> --> for TABLES[name])
    ...generated text...
    <!-- /validate -->

`validate.sh CASE` runs the case and rewrites its blocks from the case's template;
`validate.sh --check CASE` runs it and compares every number of the documented blocks with the
regenerated figure: a number passes when it equals the figure rounded as documented (within
half a unit of its last printed digit) or, for figures the case declares noisy, within the
stated relative tolerance. Text outside the numbers must equal the template.
"""
import argparse
import datetime
import hashlib
import importlib.util
import json
import math
import os
import re
import shlex
import shutil
import string
import subprocess
import sys
import time

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CASES_DIR = os.path.join(SOURCE, "tools", "validation", "cases")
DOC_FILES = ["README.md", "docs"]  # Markdown files searched for blocks (folders: every .md)
NUMBER = r"([-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?|[-+]?nan|[-+]?inf)"
BLOCK = re.compile(r"(<!-- validate:([A-Za-z0-9_\-]+)(?:/([A-Za-z0-9_\-]+))? -->\n)(.*?)(<!-- /validate -->)",
                   re.S)


class Skip(Exception):
    """A case that cannot run here (e.g. the measured data are absent)."""


class CaseError(Exception):
    pass


class Context:
    """What a case's run(v) gets: runs the build's programs in the case's own folder and
    collects figures."""

    def __init__(self, case, build, out_dir, quiet):
        self.case = case
        self.build = build
        self.dir = out_dir
        self.quiet = quiet
        self.figures = {}
        self.commands = []
        self.source = SOURCE
        self.data = os.environ.get("KNEESIM_DATA", os.path.join(SOURCE, "..", "shared", "data"))

    # --- running -------------------------------------------------------------------------
    def kneesim(self, name, args, out=True, record=None):
        """Runs `build/tools/kneesim ARGS [--out DIR/NAME]` and returns the output folder.
        The command is recorded (without --out) for the table's footer and the JSON; `record`
        (the arguments to show instead) for a run that reuses an earlier result of the same
        command, so that the footer does not depend on what the build folder already holds."""
        folder = os.path.join(self.dir, name)
        cmd = [os.path.join(self.build, "tools", "kneesim")] + list(args)
        if out:
            cmd += ["--out", folder]
        shown = args if record is None else record
        self._record(("kneesim " + " ".join(shlex.quote(a) for a in shown)).replace(SOURCE + "/", ""))
        self._call(cmd, name)
        return folder

    def kneesim_status(self, args):
        """Runs `build/tools/kneesim ARGS` as given (no --out added) in the case's folder and
        returns (exit code, stdout, stderr) whatever the exit code: for cases about refusals."""
        cmd = [os.path.join(self.build, "tools", "kneesim")] + list(args)
        self._record(("kneesim " + " ".join(shlex.quote(a) for a in args)).replace(SOURCE + "/", ""))
        env = dict(os.environ)
        env.setdefault("KNEESIM_DATA", self.data)
        p = subprocess.run(cmd, cwd=self.dir, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           text=True)
        return p.returncode, p.stdout, p.stderr

    def tool(self, name, args, record=None, env=None):
        """Runs another program of the build (e.g. tools/bench_engine) and returns its stdout;
        `env` adds environment variables."""
        exe = os.path.join(self.build, name)
        self._record(record or (name + " " + " ".join(shlex.quote(a) for a in args)).strip())
        return self._call([exe] + list(args), os.path.basename(name), env)

    def _record(self, text):
        if text not in self.commands:
            self.commands.append(text)

    def _call(self, cmd, name, extra_env=None):
        env = dict(os.environ)
        env.update(extra_env or {})
        env.setdefault("KNEESIM_DATA", self.data)
        env.setdefault("OMP_WAIT_POLICY", "passive")
        t0 = time.time()
        if not self.quiet:
            print(f"  [{self.case}] {' '.join(shlex.quote(c) for c in cmd)}", flush=True)
        p = subprocess.run(cmd, cwd=self.dir, env=env, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            raise CaseError(f"{' '.join(cmd)} exited {p.returncode}: {p.stderr.strip()[-2000:]}")
        if not self.quiet:
            print(f"  [{self.case}] {name}: {time.time() - t0:.1f} s", flush=True)
        return p.stdout

    # --- reading ---------------------------------------------------------------------------
    def json(self, *path):
        with open(os.path.join(*path)) as f:
            return json.load(f)

    def csv(self, *path):
        """Rows of a CSV file as dicts of floats where a value parses as a number."""
        import csv
        rows = []
        with open(os.path.join(*path), newline="") as f:
            for r in csv.DictReader(line for line in f if not line.startswith("#")):
                rows.append({k: _num(v) for k, v in r.items()})
        return rows

    def skip(self, reason):
        return Skip(reason)

    def require_data(self, sub):
        path = os.path.join(self.data, sub)
        if not os.path.exists(path):
            raise Skip(f"needs the measured data {path} (set KNEESIM_DATA)")
        return path

    # --- figures ---------------------------------------------------------------------------
    def figure(self, name, value, unit=""):
        """One named figure: a number (or a short text such as a named effect) with its unit."""
        if not re.match(r"^[A-Za-z_][A-Za-z0-9_]*$", name):
            raise CaseError(f"figure name '{name}' must be an identifier")
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise CaseError(f"figure '{name}' must be a number or a text, got {value!r}")
        self.figures[name] = {"value": value, "unit": unit}


def _num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return v


def load_case(name):
    path = os.path.join(CASES_DIR, name + ".py")
    if not os.path.exists(path):
        raise SystemExit(f"validate: no case '{name}' (tools/validation/cases/{name}.py); "
                         f"cases: {', '.join(all_case_names())}")
    spec = importlib.util.spec_from_file_location("kneesim_case_" + name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    for attr in ("run",):
        if not hasattr(mod, attr):
            raise SystemExit(f"validate: case {name} has no {attr}()")
    mod.NAME = name
    mod.LONG = bool(getattr(mod, "LONG", False))
    mod.NOISY = dict(getattr(mod, "NOISY", {}))
    tables = dict(getattr(mod, "TABLES", {}))
    if hasattr(mod, "TABLE"):
        tables[""] = mod.TABLE
    mod.ALL_TABLES = tables
    return mod


def all_case_names():
    return sorted(f[:-3] for f in os.listdir(CASES_DIR) if f.endswith(".py") and not f.startswith("_"))


def doc_files():
    for entry in DOC_FILES:
        p = os.path.join(SOURCE, entry)
        if os.path.isdir(p):
            for root, _, files in os.walk(p):
                for f in sorted(files):
                    if f.endswith(".md"):
                        yield os.path.join(root, f)
        elif os.path.exists(p):
            yield p


# --- templates ------------------------------------------------------------------------------
def fields(template):
    """(literal, field name, format spec) triples of a str.format template."""
    return list(string.Formatter().parse(template))


def footer(mod, commands):
    if not getattr(mod, "FOOTER_COMMANDS", True):
        return f"\n(Regenerate: `tools/scripts/validate.sh {mod.NAME}`; the commands are in the table.)\n"
    cmds = "; ".join(f"`{c}`" for c in commands)
    return f"\n(Regenerate: `tools/scripts/validate.sh {mod.NAME}`; it runs {cmds}.)\n"


def render(mod, table_name, figures, commands):
    values = {k: v["value"] for k, v in figures.items()}
    out = []
    for literal, field, spec, conv in fields(mod.ALL_TABLES[table_name].strip("\n")):
        out.append(literal)
        if field is None:
            continue
        if field not in values:
            raise CaseError(f"case {mod.NAME}: the table uses '{field}', which run() did not write")
        v = values[field]
        out.append(format(v, spec) if spec and not isinstance(v, str) else str(v))
    return "".join(out) + "\n" + footer(mod, commands)


def template_regex(mod, table_name, commands):
    parts, names = [], []
    for literal, field, spec, conv in fields(mod.ALL_TABLES[table_name].strip("\n")):
        parts.append(re.escape(literal))
        if field is not None:
            if spec and spec.endswith("%"):
                parts.append(NUMBER + "%")
            else:
                parts.append(NUMBER if (spec and spec[-1:] in "eEfFgGd") else r"(.*?)")
            names.append((field, spec))
    text = "".join(parts) + re.escape("\n" + footer(mod, commands))
    return re.compile("^" + text + "$", re.S), names


def half_unit(token):
    """Half a unit in the last printed digit of a documented number."""
    t = token.lstrip("+-")
    mant = re.split(r"[eE]", t)[0]
    exp = int(re.split(r"[eE]", t)[1]) if re.search(r"[eE]", t) else 0
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    return 0.5 * 10.0 ** (exp - decimals)


def compare(mod, table_name, documented, figures, commands):
    """Problems (sentences) of one documented block against the regenerated figures."""
    rx, names = template_regex(mod, table_name, commands)
    m = rx.match(documented)
    where = f"block validate:{mod.NAME}{'/' + table_name if table_name else ''}"
    if not m:
        regenerated = render(mod, table_name, figures, commands)
        diff = _first_diff(documented, regenerated)
        return [f"{where}: the text differs from the case's template ({diff}); "
                f"regenerate it with tools/scripts/validate.sh {mod.NAME}"]
    problems = []
    for (field, spec), token in zip(names, m.groups()):
        v = figures[field]["value"]
        unit = figures[field].get("unit", "")
        if isinstance(v, str) or not (spec and spec[-1:] in "eEfFgG%d"):
            if token != str(v):
                problems.append(f"{where}: {field} documented '{token}', regenerated '{v}'")
            continue
        d = float(token)
        shown = v * 100.0 if spec.endswith("%") else v
        if math.isnan(shown) or math.isnan(d):
            if not (math.isnan(shown) and math.isnan(d)):
                problems.append(f"{where}: {field} documented {token}, regenerated {v}")
            continue
        tol = half_unit(token.rstrip("%")) * (1 + 1e-9) + 1e-12 * abs(shown)
        rel = mod.NOISY.get(field)
        if rel is not None:
            tol = max(tol, rel * abs(shown))
        if spec[-1:] in "gGeE" and rel is None:
            # significant-digit formats drop trailing zeros ("0", "0.3"): the documented text
            # must be the regenerated value so formatted
            ok = format(v, spec) == token or abs(d - shown) <= 1e-12 * abs(shown)
        else:
            ok = abs(d - shown) <= tol
        if not ok:
            rounding = f"format '{spec}', +-{half_unit(token.rstrip('%')):g}"
            if rel is not None:
                rounding += f", or {rel:.0%} (noisy figure)"
            problems.append(f"{where}: {field} documented {token} {unit}, regenerated "
                            f"{format(v, spec)} ({v!r}) {unit}; allowed: {rounding}")
    return problems


def _first_diff(a, b):
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            return f"first difference at character {i}: documented {a[max(0, i - 20):i + 30]!r}, template {b[max(0, i - 20):i + 30]!r}"
    return "one is a prefix of the other"


# --- the command ----------------------------------------------------------------------------
def run_case(mod, args):
    out_dir = os.path.join(args.build, "validation", mod.NAME)
    os.makedirs(out_dir, exist_ok=True)
    v = Context(mod.NAME, args.build, out_dir, args.quiet)
    t0 = time.time()
    cwd = os.getcwd()
    try:
        mod.run(v)
    finally:
        os.chdir(cwd)
    result = {
        "case": mod.NAME,
        "title": getattr(mod, "TITLE", mod.NAME),
        "long": mod.LONG,
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "seconds": round(time.time() - t0, 1),
        "build": os.path.relpath(args.build, SOURCE) if args.build.startswith(SOURCE) else args.build,
        "kneesim_sha256": binary_id(args.build),
        "commands": v.commands,
        "figures": v.figures,
    }
    path = os.path.join(args.build, "validation", mod.NAME + ".json")
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(result, f, indent=1, sort_keys=False)
        f.write("\n")
    os.replace(tmp, path)
    return result


def binary_id(build):
    """The first 16 hex digits of the SHA-256 of build/tools/kneesim: which binary made a case's
    figures, so that cases run on different days can be shown to come from one build."""
    path = os.path.join(build, "tools", "kneesim")
    if not os.path.exists(path):
        return None
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()[:16]


def list_cases(names, build):
    """One line per case: name, quick/long, title, and the last run's time and date from
    build/validation/<case>.json, marked when it was not made by the current build/tools/kneesim."""
    current = binary_id(build)
    for n in names:
        mod = load_case(n)
        line = f"{n:30s} {'long ' if mod.LONG else 'quick'}  {getattr(mod, 'TITLE', '')}"
        path = os.path.join(build, "validation", n + ".json")
        if os.path.exists(path):
            with open(path) as f:
                last = json.load(f)
            made_by = last.get("kneesim_sha256")
            note = ("" if made_by == current else
                    " (binary not recorded)" if made_by is None else " (other binary)")
            line += f"  [last run {last.get('seconds', 0):.0f} s, {last.get('date', '?')}{note}]"
        print(line)


def load_result(mod, args):
    path = os.path.join(args.build, "validation", mod.NAME + ".json")
    if not os.path.exists(path):
        raise CaseError(f"{path} does not exist: run tools/scripts/validate.sh {mod.NAME} first")
    with open(path) as f:
        return json.load(f)


def blocks_of(case):
    """(file, table name, documented text) of every block of a case."""
    found = []
    for path in doc_files():
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for m in BLOCK.finditer(text):
            if m.group(2) == case:
                found.append((path, m.group(3) or "", m.group(4)))
    return found


def rewrite_blocks(mod, result):
    written = []
    for path in doc_files():
        with open(path, encoding="utf-8") as f:
            text = f.read()

        def sub(m):
            if m.group(2) != mod.NAME:
                return m.group(0)
            name = m.group(3) or ""
            if name not in mod.ALL_TABLES:
                raise CaseError(f"{os.path.relpath(path, SOURCE)}: block validate:{mod.NAME}/{name}: "
                                f"the case has no table '{name}'")
            written.append((path, name))
            return m.group(1) + render(mod, name, result["figures"], result["commands"]) + m.group(5)

        new = BLOCK.sub(sub, text)
        if new != text:
            tmp = path + ".tmp"
            with open(tmp, "w", encoding="utf-8") as f:
                f.write(new)
            os.replace(tmp, path)
    return written


def main():
    ap = argparse.ArgumentParser(prog="validate.sh", description=__doc__.split("\n\n")[0])
    ap.add_argument("cases", nargs="*", metavar="CASE", help="cases to run (default: the quick ones)")
    ap.add_argument("--check", action="store_true",
                    help="compare the documented numbers with the regenerated ones; write no docs")
    ap.add_argument("--long", action="store_true", help="also run the cases marked long")
    ap.add_argument("--long-only", action="store_true", help="run only the cases marked long")
    ap.add_argument("--from-json", action="store_true",
                    help="do not run: use build/validation/<case>.json from an earlier run")
    ap.add_argument("--json-only", action="store_true",
                    help="run and write build/validation/<case>.json, but leave the docs alone")
    ap.add_argument("--list", action="store_true", help="list the cases with their last run (time, date, whether by this build's kneesim) and exit")
    ap.add_argument("--build", default=os.path.join(SOURCE, "build"), help="build folder (default: build)")
    ap.add_argument("--quiet", action="store_true", help="print only results")
    args = ap.parse_args()
    args.build = os.path.abspath(args.build)

    names = all_case_names()
    if args.list:
        list_cases(names, args.build)
        return 0
    if args.cases:
        mods = [load_case(n) for n in args.cases]
    else:
        mods = [load_case(n) for n in names]
        mods = [m for m in mods if (m.LONG if args.long_only else (args.long or not m.LONG))]
    if not args.from_json and not os.path.exists(os.path.join(args.build, "tools", "kneesim")):
        print(f"validate: no {args.build}/tools/kneesim: build first", file=sys.stderr)
        return 2

    failed, skipped, problems = [], [], []
    for mod in mods:
        print(f"{mod.NAME}{' (long)' if mod.LONG else ''}: {getattr(mod, 'TITLE', '')}", flush=True)
        try:
            result = load_result(mod, args) if args.from_json else run_case(mod, args)
        except Skip as e:
            print(f"  skipped: {e}")
            skipped.append(mod.NAME)
            continue
        except CaseError as e:
            print(f"  FAILED to run: {e}")
            failed.append(mod.NAME)
            continue
        if not args.from_json:
            print(f"  {len(result['figures'])} figures in {result['seconds']} s -> "
                  f"{os.path.relpath(os.path.join(args.build, 'validation', mod.NAME + '.json'), SOURCE)}")
        blocks = blocks_of(mod.NAME)
        if not blocks:
            print(f"  note: no <!-- validate:{mod.NAME} --> block in the documentation yet")
        if args.check:
            for path, name, documented in blocks:
                for p in compare(mod, name, documented, result["figures"], result["commands"]):
                    problems.append(f"{os.path.relpath(path, SOURCE)}: {p}")
                    print(f"  MISMATCH {os.path.relpath(path, SOURCE)}: {p}")
        elif not args.json_only:
            for path, name in rewrite_blocks(mod, result):
                print(f"  wrote {os.path.relpath(path, SOURCE)} block validate:{mod.NAME}{'/' + name if name else ''}")
            for dst, src in getattr(mod, "IMAGES", {}).items():
                src_path = os.path.join(args.build, "validation", mod.NAME, src)
                if os.path.exists(src_path):
                    shutil.copyfile(src_path, os.path.join(SOURCE, dst))
                    print(f"  copied {dst}")
                else:
                    print(f"  note: no {src_path} to copy to {dst}")
    print(f"validate: {len(mods) - len(failed) - len(skipped)} case(s) run, {len(skipped)} skipped"
          f"{' (' + ', '.join(skipped) + ')' if skipped else ''}, {len(failed)} failed"
          f"{' (' + ', '.join(failed) + ')' if failed else ''}"
          + (f", {len(problems)} documented number(s) differ" if args.check else ""))
    return 1 if (failed or problems) else 0


if __name__ == "__main__":
    sys.exit(main())
