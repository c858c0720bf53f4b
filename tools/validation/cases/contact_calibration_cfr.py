"""The shipped CFR-PEEK law of the built-in implant: kneesim calibrate-contact with the deformable
reference on fine surfaces (0.25 mm facets, 0.2 mm distance field: the surfaces on which
CFR-PEEK's peak pressure converges, mesh_convergence_cfr), the rigid runs on the default ones
(1 mm, 0.4 mm: what a user's rigid run has); fitted on 0-30 % of the cycle, judged held out on
30-60 %. contact_calibration's generic CFR-PEEK row is the same fit against a reference on the
default surfaces, whose peak follows the facets' ridges."""
import importlib.util
import os

_spec = importlib.util.spec_from_file_location(
    "kneesim_contact_calibration", os.path.join(os.path.dirname(__file__), "contact_calibration.py"))
CAL = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(CAL)

TITLE = "Calibrated rigid contact law, CFR-PEEK on the built-in implant (reference on fine surfaces)"
LONG = True  # one deformable cycle on about 40 000 elements on fine surfaces (4-10 minutes) and
# about 200 short rigid runs; the deformable run tools/scripts/calibrate_contact_laws.sh left in
# build/contact_laws/generic_cfr-peek is reused when it is there
IMAGES = {"docs/img/contact_calibration_cfr.png": "gen_cfr_fine/calibration.png"}

SURFACES = ["--reference-edge-mm", "0.25", "--reference-sdf-mm", "0.2"]


def run(v):
    args = ["calibrate-contact", "--material", "cfr-peek"] + SURFACES
    reuse = CAL.deformable_run(v, "gen_cfr_fine", "generic_cfr-peek")
    d = v.kneesim("gen_cfr_fine", args + reuse, record=args)
    CAL.record_fit(v, "gen_cfr_fine", d)


TABLE = (CAL.ALL_HEAD + CAL._row("generic, CFR-PEEK, reference on 0.25 mm facets", "gen_cfr_fine")
         + "\n" + CAL._detail("gen_cfr_fine"))
