#include "app/viewer/formula_draft.h"

#include <filesystem>
#include <stdexcept>

#include "core/surface/expression/expression.h"

namespace dynamesh {
namespace {

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

bool breaks_after(char c) {
  return c == '*' || c == '/' || c == ',' || c == '(' || c == ';';
}

// What a field holds as one option value: the settings file and the command line are line
// based, and muparser reads a line break as nothing it knows. A break after an operator
// (where wrap_formula puts them) joins the lines as they were; any other becomes a space, so
// two names on either side never merge into one.
std::string one_line(const std::string& field) {
  const std::string in = trimmed(field);
  std::string out;
  for (char c : in) {
    if (c == '\r') continue;
    if (c == '\n') {
      while (!out.empty() && out.back() == ' ') out.pop_back();
      if (!out.empty() && !breaks_after(out.back())) out.push_back(' ');
    } else {
      out.push_back(c == '\t' ? ' ' : c);
    }
  }
  return out;
}

std::string parametric_text(const std::array<std::string, 3>& xyz) {
  return one_line(xyz[0]) + "; " + one_line(xyz[1]) + "; " + one_line(xyz[2]);
}

// The variables and the name the core gives each kind's formulas (expr_scene.cpp), so the
// panel's messages are the ones the CLI prints.
std::vector<std::string> variables_of(ExprKind kind) {
  switch (kind) {
    case ExprKind::kImplicit:
      return {"x", "y", "z", "t"};
    case ExprKind::kHeight:
      return {"x", "z", "t"};
    case ExprKind::kParametric:
      return {"u", "v", "t"};
  }
  return {};
}

// Expression's message without its "ROLE 'FORMULA': " prefix: shown under the field that
// holds the formula, repeating it only pushes the reason off the panel.
std::string formula_error(const std::string& formula, const std::vector<std::string>& variables,
                          const std::string& role) {
  try {
    const Expression parsed({formula}, variables, role);
    return {};
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what(), prefix = role + " '" + formula + "': ";
    if (message.rfind(prefix, 0) == 0) return message.substr(prefix.size());
    if (message.rfind(role + " ", 0) == 0) return message.substr(role.size() + 1);
    return message;
  }
}

std::string options_error(const TextOptions& options) {
  try {
    parse_expr_options(options);
    return {};
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

// One line of wrap_formula: the longest head up to `columns` that ends at a break.
void wrap_line(std::string line, std::size_t columns, std::string& out) {
  while (line.size() > columns) {
    // The head is line[0, cut), the rest starts at next: the last break that keeps the head
    // within `columns`, else the first there is.
    std::size_t cut = std::string::npos, next = 0;
    for (std::size_t i = 1; i < line.size(); ++i) {
      std::size_t end = 0;
      if (line[i] == ' ') {
        end = i;
      } else if (breaks_after(line[i]) && i + 1 < line.size()) {
        end = i + 1;
      } else {
        continue;
      }
      if (end > columns && cut != std::string::npos) break;
      cut = end, next = i + 1;
      if (end > columns) break;
    }
    if (cut == std::string::npos) break;
    std::string head = trimmed(line.substr(0, cut)), rest = trimmed(line.substr(next));
    if (head.empty() || rest.empty()) break;
    out += head + "\n";
    line = rest;
  }
  out += line;
}

}  // namespace

const char* formula_kind_key(ExprKind kind) {
  switch (kind) {
    case ExprKind::kImplicit:
      return "implicit";
    case ExprKind::kHeight:
      return "height";
    case ExprKind::kParametric:
      return "parametric";
  }
  return "implicit";
}

std::string wrap_formula(const std::string& formula, std::size_t columns) {
  if (columns == 0) return formula;
  std::string out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = formula.find('\n', start);
    wrap_line(formula.substr(start, end - start), columns, out);
    if (end == std::string::npos) break;
    out += '\n';
    start = end + 1;
  }
  return out;
}

FormulaDraft formula_draft_from_text(const TextOptions& text, std::size_t wrap_columns) {
  FormulaDraft d;
  d.source = text;
  if (text.empty()) {
    d.implicit = wrap_formula(d.implicit, wrap_columns);
    return d;
  }
  std::string domain;
  bool periodic_given = false;
  for (const auto& [key, value] : text) {
    if (key == "implicit") {
      d.kind = ExprKind::kImplicit;
      d.implicit = wrap_formula(value, wrap_columns);
    } else if (key == "height") {
      d.kind = ExprKind::kHeight;
      d.height = wrap_formula(value, wrap_columns);
    } else if (key == "parametric") {
      d.kind = ExprKind::kParametric;
      // X;Y;Z into three fields; more than two semicolons stay in Z, where the check says so.
      std::size_t start = 0;
      for (int i = 0; i < 3; ++i) {
        const std::size_t semicolon = i < 2 ? value.find(';', start) : std::string::npos;
        d.parametric[i] = wrap_formula(
            trimmed(start <= value.size() ? value.substr(start, semicolon - start) : ""),
            wrap_columns);
        start = semicolon == std::string::npos ? value.size() + 1 : semicolon + 1;
      }
    } else if (key == "bounds") {
      d.bounds = value;
    } else if (key == "domain") {
      domain = value;  // whose domain it is depends on the formula, which may come later
    } else if (key == "periodic") {
      periodic_given = true;
      d.periodic_u = value.find('u') != std::string::npos;
      d.periodic_v = value.find('v') != std::string::npos;
    } else if (key == "base-mesh") {
      d.base_mesh = value;
    }
  }
  if (d.kind == ExprKind::kParametric) {
    d.parametric_domain = domain;
    if (!periodic_given) d.periodic_u = d.periodic_v = false;
  } else if (d.kind == ExprKind::kHeight) {
    d.height_domain = domain;
  }
  return d;
}

TextOptions formula_draft_text(const FormulaDraft& d) {
  TextOptions text;
  switch (d.kind) {
    case ExprKind::kImplicit:
      text.emplace_back("implicit", one_line(d.implicit));
      text.emplace_back("bounds", one_line(d.bounds));
      if (!trimmed(d.base_mesh).empty()) text.emplace_back("base-mesh", trimmed(d.base_mesh));
      break;
    case ExprKind::kHeight:
      text.emplace_back("height", one_line(d.height));
      if (!trimmed(d.height_domain).empty()) text.emplace_back("domain", one_line(d.height_domain));
      break;
    case ExprKind::kParametric:
      text.emplace_back("parametric", parametric_text(d.parametric));
      text.emplace_back("domain", one_line(d.parametric_domain));
      if (d.periodic_u || d.periodic_v)
        text.emplace_back("periodic", std::string(d.periodic_u ? "u" : "") +
                                          std::string(d.periodic_v ? "v" : ""));
      break;
  }
  return text;
}

bool formula_draft_edited(const FormulaDraft& draft) {
  return formula_draft_text(draft) !=
         formula_draft_text(formula_draft_from_text(draft.source.value_or(TextOptions{})));
}

FormulaCheck check_formula_draft(const FormulaDraft& d) {
  FormulaCheck check;
  const std::vector<std::string> variables = variables_of(d.kind);
  const std::string key = formula_kind_key(d.kind);
  switch (d.kind) {
    case ExprKind::kImplicit:
      check.formula[0] = formula_error(one_line(d.implicit), variables, "implicit formula");
      if (trimmed(d.bounds).empty())
        check.extent = "give the bounds xmin,ymin,zmin,xmax,ymax,zmax: a box around the surface";
      else
        check.extent = options_error({{key, "0"}, {"bounds", one_line(d.bounds)}});
      if (const std::string file = trimmed(d.base_mesh); !file.empty()) {
        std::error_code error;
        if (!std::filesystem::is_regular_file(file, error))
          check.base_mesh = "no such file: " + file + " (relative to " +
                            std::filesystem::current_path(error).string() + ")";
      }
      break;
    case ExprKind::kHeight:
      check.formula[0] = formula_error(one_line(d.height), variables, "height formula");
      if (!trimmed(d.height_domain).empty())
        check.extent = options_error({{key, "0"}, {"domain", one_line(d.height_domain)}});
      break;
    case ExprKind::kParametric:
      for (int i = 0; i < 3; ++i) {
        // The three are sent joined by ';': one more would shift Y into Z.
        check.formula[i] = d.parametric[i].find(';') != std::string::npos
                               ? "one formula per field: no ';'"
                               : formula_error(one_line(d.parametric[i]), variables,
                                               std::string(1, "XYZ"[i]) + "(u, v, t)");
      }
      check.extent =
          trimmed(d.parametric_domain).empty()
              ? "give the domain umin,umax,vmin,vmax (e.g. 0,2*pi,-1,1)"
              : options_error({{key, "0;0;0"}, {"domain", one_line(d.parametric_domain)}});
      break;
  }
  if (check.ok()) check.options = options_error(formula_draft_text(d));
  return check;
}

}  // namespace dynamesh
