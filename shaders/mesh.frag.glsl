#version 330 core
// Mesh fragment stage: base colour (flat tint or a colour map of the scalar), two-light
// shading lit from whichever side faces the eye, a different tint on the back faces of the
// flat-tinted surface (a colour map shows its bar's colours from both sides: an open
// surface is seen from either), and the wireframe overlay.
// A volume scene (mri) is coloured per fragment from its scan (issue 14): the world position
// goes through the inverse of the volume's placement (sform/qform) into a 3-D texture —
// trilinear intensities, or the label atlas's region (nearest voxel, flat per region) — so the
// picture follows the scan, not the mesh's triangles.
in FragmentData {
  vec3 view_position;
  vec3 view_normal;
  float scalar;
  vec3 world_position;
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
// 0: the per-vertex scalar; 1: intensity from u_intensity; 2: region from u_labels.
uniform int u_volume_mode;
uniform sampler3D u_intensity;     // R32F, linear filtering = trilinear between voxel centres
uniform mat4 u_world_to_texture;   // world mm -> intensity texture coordinates
uniform isampler3D u_labels;       // R32I region index per voxel
uniform mat4 u_world_to_label;     // world mm -> label voxel index (centres at integers)

out vec4 frag_color;

// The scalar here: interpolated, or for a category the value of the nearest corner.
float scalar_value() {
  if (!u_categorical) return f_in.scalar;
  vec3 b = f_in.barycentric;
  if (b.x >= b.y && b.x >= b.z) return f_in.corner_scalars.x;
  return b.y >= b.z ? f_in.corner_scalars.y : f_in.corner_scalars.z;
}

// Distinct, stable colours for region indices: hues a golden angle apart, two lightness
// bands so that neighbouring indices (left / right of one AAL region) differ.
vec3 region_color(int label) {
  if (label <= 0) return u_surface_color;
  float h = fract(float(label) * 0.61803398875);
  float v = (label % 2 == 0) ? 0.95 : 0.72;
  vec3 k = clamp(abs(mod(h * 6.0 + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
  return v * mix(vec3(1.0), k, 0.7);
}

int region_here() {
  ivec3 size = textureSize(u_labels, 0);
  ivec3 v = ivec3(floor((u_world_to_label * vec4(f_in.world_position, 1.0)).xyz + 0.5));
  if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, size))) return 0;
  return texelFetch(u_labels, v, 0).r;
}

vec3 base_color() {
  if (u_volume_mode == 2) return region_color(region_here());
  if (!u_use_colormap) return u_surface_color;
  float value = u_volume_mode == 1
                    ? texture(u_intensity, (u_world_to_texture * vec4(f_in.world_position, 1.0)).xyz).r
                    : scalar_value();
  float t = (value - u_scalar_range.x) / max(u_scalar_range.y - u_scalar_range.x, 1e-30);
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
    if (!u_use_colormap && u_volume_mode != 2) color = mix(color, u_backface_tint, 0.65);
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
