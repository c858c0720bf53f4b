"""One interpreter for all the plots of a kneesim command (engine/io/plot.h, PlotSession).

Imports matplotlib at once (while the simulation runs), then reads one JSON request per line
from stdin, {"script": PATH, "args": [...]}, runs the script as `python3 PATH ARGS...` would
(as __main__, with sys.argv set and its folder on sys.path), and answers on file descriptor 3
with one line per request, "ok", "disk full" (the script exited with plotio.DISK_FULL) or
"fail", in order. matplotlib's settings are restored and
every figure closed after each script, so a script sees the state a fresh interpreter gives.

usage: plot_server.py   (started by kneesim; stdin and fd 3 are its socket)
"""
import json
import os
import runpy
import sys
import traceback

DISK_FULL = 3  # plotio.DISK_FULL, engine/io/plot.h kPlotDiskFull


def main():
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import matplotlib.tri  # noqa: F401  (wear.py's depth map)
        import plotio  # noqa: F401
    except Exception:
        matplotlib = plt = None  # every script then fails on its own import and says why
    replies = os.fdopen(3, "w")
    for line in sys.stdin:
        request = json.loads(line)
        code = run_script(request["script"], request["args"], matplotlib, plt)
        replies.write("ok\n" if code == 0 else "disk full\n" if code == DISK_FULL else "fail\n")
        replies.flush()


def run_script(script, args, matplotlib, plt):
    saved_argv = sys.argv
    sys.argv = [script] + list(args)
    try:
        if matplotlib is None:
            runpy.run_path(script, run_name="__main__")
        else:
            with matplotlib.rc_context():
                runpy.run_path(script, run_name="__main__")
        return 0
    except SystemExit as e:
        return 0 if e.code is None else e.code if isinstance(e.code, int) else 1
    except Exception:
        traceback.print_exc()
        return 1
    finally:
        sys.argv = saved_argv
        if plt is not None:
            plt.close("all")
        sys.stdout.flush()
        sys.stderr.flush()


if __name__ == "__main__":
    main()
