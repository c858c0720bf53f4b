#!/usr/bin/env python3
"""Every command's report.html in a real browser (headless Chromium, nothing downloaded).

For each case: runs the kneesim command into a fresh folder, opens DIR/report.html#selfcheck
with `chromium --dump-dom` (the page renders, moves its slider and writes what it found into
<pre id="kneesim-selfcheck">, analysis/report/viewer.js) and checks that
  - the page reported no uncaught error and no console.error, and Chromium's log shows no
    uncaught exception;
  - the 3D canvas is not blank: the luminance variance of its pixels, read in the page, and of
    the same region of a real screenshot (`chromium --screenshot`, decoded here with zlib) are
    above 50 (a uniform canvas gives 0; the default run's view gives about 1000);
  - moving the slider to the step whose field maximum differs most changes > 1 % of the pixels;
  - every number the page shows equals the value at its JSON pointer in DIR/summary.json, to
    the decimals shown (|shown - value x scale| <= half a unit of the last digit; compare:
    DIR/comparison.json);
  - the page fetched nothing (the browser's resource timing list is empty), has no element
    that loads a file, and is under 8 MB.
Exit 77 (ctest: skipped) with a reason when Chromium is not installed.

usage: report_browser_test.py --kneesim PATH --work DIR [--screenshots DIR] [CASE...]
"""
import argparse
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync",
                  "--enable-unsafe-swiftshader", "--hide-scrollbars"]

# name -> (kneesim arguments after the command's output folder is appended)
CASES = {
    "run": ["run", "--no-plots"],
    # four geometry updates: the slider has five steps (new insert and four worn)
    "wear": ["wear", "--cycles", "1000000", "--update-every", "250000", "--no-plots"],
    "compare": ["compare", "--cycles", "500000", "--update-every", "250000", "--no-plots",
                "--no-break-even"],
    # the commands without a 3D view share one page builder (analysis/report/summary_report.h)
    "bor": ["bor"],
    "study": ["study", "--method", "lhs", "--trials", "3", "--quiet"],
}

# the file whose numbers the page shows (summary.json unless named here)
SUMMARY = {"compare": "comparison.json"}


def find_chromium():
    for c in (os.environ.get("KNEESIM_CHROMIUM"), "/usr/bin/chromium", shutil.which("chromium")):
        if c and os.path.exists(c):
            return c
    return None


def chromium(browser, args, timeout=120):
    with tempfile.TemporaryDirectory(prefix="kneesim-chromium-") as profile:
        r = subprocess.run([browser] + CHROMIUM_FLAGS + ["--user-data-dir=" + profile] + args,
                           capture_output=True, text=True, timeout=timeout)
    return r


def png_pixels(path):
    """(width, height, rows of RGB tuples) of an 8-bit RGB/RGBA non-interlaced PNG."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
            assert depth == 8 and ctype in (2, 6) and interlace == 0, (depth, ctype, interlace)
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, bpp, rows


def region_variance(path, rect):
    w, h, bpp, rows = png_pixels(path)
    x0, y0, rw, rh = (int(round(v)) for v in rect)
    s = s2 = n = 0
    for y in range(max(0, y0 + 2), min(h, y0 + rh - 2), 2):
        line = rows[y]
        for x in range(max(0, x0 + 2), min(w, x0 + rw - 2), 2):
            r, g, b = line[bpp * x], line[bpp * x + 1], line[bpp * x + 2]
            lum = 0.299 * r + 0.587 * g + 0.114 * b
            s += lum
            s2 += lum * lum
            n += 1
    assert n > 0, "the canvas is outside the screenshot"
    m = s / n
    return s2 / n - m * m


def lookup(summary, pointer):
    node = summary
    for part in pointer.lstrip("/").split("/"):
        part = part.replace("~1", "/").replace("~0", "~")
        node = node[int(part)] if isinstance(node, list) else node[part]
    return node


def check_case(name, args, opts, browser):
    failures = []
    out = os.path.join(opts.work, name)
    shutil.rmtree(out, ignore_errors=True)
    cmd = [opts.kneesim] + args + ["--out", out]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        return ["%s: %s exited %d: %s" % (name, " ".join(cmd), r.returncode, r.stderr[-500:])]
    page = os.path.join(out, "report.html")
    if not os.path.exists(page):
        return ["%s: %s wrote no report.html" % (name, " ".join(cmd))]
    html = open(page, encoding="utf-8").read()
    size_mb = os.path.getsize(page) / 1e6
    if size_mb > 8:
        failures.append("%s: report.html is %.1f MB (limit 8)" % (name, size_mb))
    # no element that loads something (the URLs in three.js's comments and namespace names
    # fetch nothing; what the page did fetch is checked in the browser below)
    for ref in re.findall(r"<(?:script|img|link|iframe|source)\b[^>]*\b(?:src|href)\s*=[^>]*>",
                          html):
        failures.append("%s: the page loads %s (must be self-contained)" % (name, ref))
    summary_name = SUMMARY.get(name, "summary.json")
    summary = json.load(open(os.path.join(out, summary_name)))

    url = "file://" + os.path.abspath(page)
    d = chromium(browser, ["--enable-logging=stderr", "--v=0", "--window-size=1280,1000",
                           "--dump-dom", url + "#selfcheck"])
    m = re.search(r'<pre id="kneesim-selfcheck">(.*?)</pre>', d.stdout, re.S)
    if not m or not m.group(1).strip():
        return failures + ["%s: the page wrote no self-check (chromium exit %d): %s"
                           % (name, d.returncode, d.stderr[-800:])]
    check = json.loads(m.group(1).replace("&quot;", '"').replace("&lt;", "<")
                       .replace("&gt;", ">").replace("&amp;", "&"))
    for line in d.stderr.splitlines():
        if "CONSOLE" in line and "Uncaught" in line:
            failures.append("%s: console: %s" % (name, line.strip()))
    if check.get("resources"):
        failures.append("%s: the page fetched %s (must be self-contained)"
                        % (name, check["resources"]))
    if check.get("errors"):
        failures.append("%s: page errors: %s" % (name, check["errors"]))
    if check.get("scene"):
        if not check.get("webgl"):
            failures.append("%s: no WebGL context" % name)
        else:
            var_page = check["canvas"]["variance"]
            if var_page <= 50:
                failures.append("%s: the canvas is blank (variance %.1f)" % (name, var_page))
            shot = os.path.join(out, "report_screenshot.png")
            rect = check["canvas"]["rect"]
            height = max(1000, int(rect[1] + rect[3] + 40))  # the whole canvas in the picture
            s = chromium(browser, ["--window-size=1280,%d" % height, "--screenshot=" + shot, url])
            if not os.path.exists(shot):
                failures.append("%s: no screenshot (chromium exit %d)" % (name, s.returncode))
            else:
                var_shot = region_variance(shot, check["canvas"]["rect"])
                if var_shot <= 50:
                    failures.append("%s: the screenshot's canvas is blank (variance %.1f)"
                                    % (name, var_shot))
                print("%s: canvas variance %.0f in the page, %.0f in the screenshot"
                      % (name, var_page, var_shot))
            sl = check["slider"]
            if sl["steps"] < 2 or sl["changed_fraction"] <= 0.01:
                failures.append("%s: moving the slider from step %d to %d changed %.2f %% of "
                                "the pixels (%d steps)" % (name, sl["from"], sl["to"],
                                                           100 * sl["changed_fraction"],
                                                           sl["steps"]))
            print("%s: slider step %d -> %d changes %.1f %% of the canvas"
                  % (name, sl["from"], sl["to"], 100 * sl["changed_fraction"]))
    elif opts.require_scene.get(name, False):
        failures.append("%s: the report has no 3D view" % name)
    if not check["numbers"]:
        failures.append("%s: the page shows no key numbers" % name)
    for n in check["numbers"]:
        try:
            value = float(lookup(summary, n["key"])) * n["scale"]
        except (KeyError, IndexError, ValueError, TypeError):
            failures.append("%s: shown number %s is not in %s" % (name, n["key"], summary_name))
            continue
        text = n["text"].strip()
        decimals = len(text.split(".")[1]) if "." in text else 0
        if abs(float(text) - value) > 0.5 * 10 ** -decimals * (1 + 1e-9):
            failures.append("%s: %s shows %s, %s has %r (x %g)"
                            % (name, n["key"], text, summary_name, value / n["scale"], n["scale"]))
    print("%s: %d numbers equal %s, %.2f MB" % (name, len(check["numbers"]), summary_name,
                                                size_mb))
    if opts.screenshots:
        os.makedirs(opts.screenshots, exist_ok=True)
        chromium(browser, ["--window-size=1280,%d" % opts.screenshot_height,
                           "--screenshot=" + os.path.join(opts.screenshots,
                                                          "report_%s.png" % name), url])
    return failures


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--kneesim", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--screenshots", help="also save a full-page screenshot per case here")
    ap.add_argument("--screenshot-height", type=int, default=2400)
    ap.add_argument("cases", nargs="*")
    opts = ap.parse_args()
    opts.require_scene = {"run": True, "wear": True, "compare": True}
    browser = find_chromium()
    if not browser:
        print("SKIP: Chromium is not installed (/usr/bin/chromium, Debian package chromium; "
              "tools/scripts/setup.sh installs it): the reports cannot be opened in a browser")
        return 77
    os.makedirs(opts.work, exist_ok=True)
    failures = []
    for name in opts.cases or CASES:
        failures += check_case(name, CASES[name], opts, browser)
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
