// FormulaDraft: the fields of the viewer's formula panel (the `expr` scene) as a person edits
// them, and their conversion from and to the scene's text options — the keys make_scene reads
// and dynamesh-cli's --implicit, --bounds, ... fill.
//
// The draft is not what runs: SimulationControls::scene_text is. The panel copies the draft
// there when it is applied, and only a draft that checks (check_formula_draft) is applied, so a
// half-typed formula never reaches the worker thread and the running surface goes on.
// Every kind keeps its own fields, so trying another kind and coming back loses nothing.
//
// The draft lives in ViewerState (reset with it) but is not written to the settings file:
// the file keeps the applied scene_text, from which the fields are filled again at start.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "core/surface/expression/expr_options.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {

// The panel's starting formulas for the kinds the core gives no default for. The parametric
// one is the wobbling tube of assets/examples, x = sin u, z = cos u so that Su x Sv faces out.
inline constexpr const char* kDefaultHeightFormula = "0.15*sin(3*x + 2*pi*t)*cos(2*z)";
inline constexpr std::array<const char*, 3> kDefaultParametricFormulas = {
    "sin(u)*(1 + 0.3*sin(2*pi*t)*cos(3*v))", "v", "cos(u)*(1 + 0.3*sin(2*pi*t)*cos(3*v))"};

struct FormulaDraft {
  ExprKind kind = ExprKind::kImplicit;
  // Implicit F(x, y, z, t) = 0: the expr scene's own default (what it runs without options).
  std::string implicit = kDefaultImplicitFormula;
  std::string bounds = "-1.5,-1.5,-1.5,1.5,1.5,1.5";
  std::string base_mesh;  // empty: the built-in box of quads
  // Height field y = f(x, z, t).
  std::string height = kDefaultHeightFormula;
  std::string height_domain = "-1,1,-1,1";  // empty: the scene's default, the same square
  // Parametric (X, Y, Z)(u, v, t): a tube that closes up around u.
  std::array<std::string, 3> parametric = {
      kDefaultParametricFormulas[0], kDefaultParametricFormulas[1], kDefaultParametricFormulas[2]};
  std::string parametric_domain = "0,2*pi,-1,1";
  bool periodic_u = true, periodic_v = false;
  // The scene text these fields were filled from or last applied as; none before the panel
  // first shows them. When the controls' text changes behind the panel's back (command line,
  // settings restored or reset, another scene), the fields follow it.
  std::optional<TextOptions> source;

  bool operator==(const FormulaDraft&) const = default;
};

// The fields for `text` (empty: the defaults above, as the scene without options runs them).
// Keys the draft has no field for are left out: building the scene reports them. With
// `wrap_columns` > 0 the formulas are broken into lines of about that many characters (see
// wrap_formula), so that a narrow field shows them whole.
FormulaDraft formula_draft_from_text(const TextOptions& text, std::size_t wrap_columns = 0);
// The text options of the draft's kind, one line per value (line breaks typed into a formula
// become spaces), what the panel sends to the simulation.
TextOptions formula_draft_text(const FormulaDraft& draft);
// True when the fields say something else than `draft.source` (none: the defaults).
bool formula_draft_edited(const FormulaDraft& draft);

// One line per field, empty where the field is fine. Cheap (formulas are parsed, never
// evaluated over the bounds; a base mesh is looked for, not read): the panel calls it on every
// frame it draws, on the UI thread.
struct FormulaCheck {
  std::array<std::string, 3> formula;  // [0]: the implicit or height formula; X, Y, Z
  std::string extent;                  // bounds (implicit) or domain
  std::string base_mesh;
  std::string options;  // what no single field is to blame for

  bool ok() const {
    return formula[0].empty() && formula[1].empty() && formula[2].empty() && extent.empty() &&
           base_mesh.empty() && options.empty();
  }
};
FormulaCheck check_formula_draft(const FormulaDraft& draft);

// `formula` with line breaks put at spaces, or else after * / , ( ; where a line would grow
// past `columns`: places where a break (a space once applied) cannot change the meaning —
// never inside a name or a number such as 1e-3. Lines already short enough are kept.
std::string wrap_formula(const std::string& formula, std::size_t columns);

// The text option key of a kind ("implicit", "height", "parametric").
const char* formula_kind_key(ExprKind kind);

}  // namespace dynamesh
