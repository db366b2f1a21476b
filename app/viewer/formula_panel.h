// The formula section of the viewer's panel, shown for the `expr` scene: an example library,
// the kind of surface, its formula fields and extent, each checked while it is typed with
// the reason in red under the field. Enter (or Apply) sends a draft that checks to the
// simulation; the surface is built on the worker thread, and what only building finds (no
// zero crossing, NaN on the bounds, a broken base mesh, a later time failing) comes back as
// PanelInfo::error, shown under the formula while the last good mesh stays on screen.
#pragma once

#include "app/viewer/viewer_panel.h"

namespace dynamesh {

// Edits state.formula; true when it changed state.controls.scene_text (the caller re-runs).
bool formula_section(ViewerState& state, const PanelInfo& info);

}  // namespace dynamesh
