// A commented starting config for one's own implant meshes (`kneesim config --template`): the
// [implant.mesh] keys with what each means and how to find its value, then the rig and the
// material. Every key it sets is a registered key; a test loads it with real mesh paths.
#pragma once

#include <string>

namespace kneesim::models {

// the template's TOML text; FEMUR and INSERT are written into implant.mesh.femur / insert
// (placeholders when empty)
std::string config_template(const std::string& femur = "", const std::string& insert = "");

}  // namespace kneesim::models
