#include "models/config_template.h"

namespace kneesim::models {

std::string config_template(const std::string& femur, const std::string& insert) {
  const std::string f = femur.empty() ? "my_femoral_component.stl" : femur;
  const std::string i = insert.empty() ? "my_tibial_insert.stl" : insert;
  return R"(# kneesim config for your own implant (kneesim config --template).
# 1. Set the two mesh files and their unit below.
# 2. Run `kneesim implant check THIS.toml`: it loads the meshes as a run does, refuses what the
#    rig cannot use (exit 2, one sentence), prints sizes, the articular area, the flexion axis
#    and the gaps, warns about the frame, and draws DIR/implant_views.png.
# 3. Fix rotation_deg and femur_origin_mm as its warnings say, check again until it warns
#    nothing you do not expect, then `kneesim run THIS.toml`.
# Every key: docs/config-reference.md. Paths are relative to this file; ${KNEESIM_DATA} is
# expanded.

[implant]
kind = "mesh"

[implant.mesh]
femur = ")" + f + R"("      # femoral component: STL, OBJ or PLY
insert = ")" + i + R"("     # tibial insert, closed (watertight) for the wear volume
units = "m"                # length unit of both files: "m" or "mm"
# rotation about x, then y, then z (deg) from the files' axes into the project frame:
# +x anterior, +y superior, +z lateral (right knee). Files with +X posterior and +Z medial
# (the Grand Challenge meshes) need [0.0, 180.0, 0.0]; implant check warns when the femoral
# flange points posterior.
rotation_deg = [0.0, 0.0, 0.0]
left_knee = false          # true mirrors z (a left knee into the right-knee frame)
# the flexion-extension axis (along z) through the femoral component, in the rotated frame of
# the files [mm]; the femur flexes about it. [0, 0, 0] is the files' own origin, rarely right:
# implant check fits the centre of the distal condylar arcs and prints it.
femur_origin_mm = [0.0, 0.0, 0.0]
insert_base_y_mm = 0.0     # height of the insert's base plane; layer thickness is measured from it
articular_min_normal_y = 0.35  # insert faces steeper than this are not articular
insert_closed = true       # false accepts an open insert (no wear volume then)

[rig]
preset = "stanmore"        # stanmore | materials_study | displacement | iso (user guide: rig presets)

[material]
name = "uhmwpe"            # uhmwpe | peek | cfr-peek, or your own [materials.<name>] table
)";
}

}  // namespace kneesim::models
