#version 330 core
// Mesh fragment stage: base colour (flat tint or a colour map of the scalar), two-light
// shading lit from whichever side faces the eye, a different tint on the back faces of the
// flat-tinted surface (a colour map shows its bar's colours from both sides: an open
// surface is seen from either), and the wireframe overlay.
in FragmentData {
  vec3 view_position;
  vec3 view_normal;
  float scalar;
  noperspective vec3 edge_distance;
  flat vec3 corner_scalars;
  vec3 barycentric;
} f_in;

uniform bool u_use_colormap;
uniform bool u_categorical;    // the scalar is a category: each corner's region is flat
uniform sampler2D u_colormap;  // 256 x 1, the map from 0 to 1
uniform vec2 u_scalar_range;   // scalar values mapped to the map's two ends
uniform vec3 u_surface_color;
uniform vec3 u_backface_tint;
uniform bool u_wireframe;
uniform float u_wire_width;    // pixels
uniform vec3 u_wire_color;
uniform vec3 u_light2_direction;  // view space, towards the light
uniform float u_ambient;

out vec4 frag_color;

// The scalar here: interpolated, or for a category the value of the nearest corner.
float scalar_value() {
  if (!u_categorical) return f_in.scalar;
  vec3 b = f_in.barycentric;
  if (b.x >= b.y && b.x >= b.z) return f_in.corner_scalars.x;
  return b.y >= b.z ? f_in.corner_scalars.y : f_in.corner_scalars.z;
}

vec3 base_color() {
  if (!u_use_colormap) return u_surface_color;
  float t = (scalar_value() - u_scalar_range.x) / max(u_scalar_range.y - u_scalar_range.x, 1e-30);
  return texture(u_colormap, vec2(clamp(t, 0.0, 1.0), 0.5)).rgb;
}

float lambert_blinn(vec3 n, vec3 to_light, vec3 to_eye, out float specular) {
  float diffuse = max(dot(n, to_light), 0.0);
  vec3 h = normalize(to_light + to_eye);
  specular = diffuse > 0.0 ? pow(max(dot(n, h), 0.0), 48.0) : 0.0;
  return diffuse;
}

void main() {
  vec3 n = normalize(f_in.view_normal);
  vec3 to_eye = normalize(-f_in.view_position);
  vec3 color = base_color();
  if (!gl_FrontFacing) {
    n = -n;
    if (!u_use_colormap) color = mix(color, u_backface_tint, 0.65);
  }
  // Headlight from the eye, plus a dimmer fixed light so that shapes read in depth.
  float s1, s2;
  float d1 = lambert_blinn(n, to_eye, to_eye, s1);
  float d2 = lambert_blinn(n, normalize(u_light2_direction), to_eye, s2);
  vec3 lit = color * (u_ambient + 0.65 * d1 + 0.35 * d2) + vec3(0.18 * s1 + 0.12 * s2);
  if (u_wireframe) {
    float d = min(f_in.edge_distance.x, min(f_in.edge_distance.y, f_in.edge_distance.z));
    // One-pixel smooth falloff outside the core width: crisp but not aliased.
    float coverage = 1.0 - smoothstep(0.5 * u_wire_width - 0.5, 0.5 * u_wire_width + 0.5, d);
    lit = mix(lit, u_wire_color, coverage);
  }
  frag_color = vec4(clamp(lit, 0.0, 1.0), 1.0);
}
